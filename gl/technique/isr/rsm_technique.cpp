#include "gl/technique/isr/rsm_technique.h"

#include <algorithm>

#include "gl/frame/rsm.h"
#include "gl/technique/isr/vpl_gather.h"
#include "gl/technique/isr/vpl_sample.h"

namespace bounce::gl {

namespace {

// RSM -> regular-grid VPLs -> full-screen gather. vpls < 0: every RSM texel is a VPL (rsm-full).
class RsmGather final : public Technique {
public:
    RsmGather(const RsmSettings& settings, int vpls) : rsm_(settings), vpls_(vpls) {}

    void render(Frame& frame, PassTimers& timers) override
    {
        rsm_.render(frame, timers);
        const int side = vpls_ < 0 ? rsm_.size() : VplSampler::sideFor(vpls_, rsm_.viewCount(), rsm_.size());
        reserveVplCache(cache_, side * side * std::max(rsm_.viewCount(), 1));
        count_ = sampler_.sample(rsm_, cache_, side, timers);
        gather_.gather(frame, cache_, count_, timers);
    }

    std::vector<Counter> counters() const override { return {{"vpls", double(count_)}}; }

private:
    RsmPass rsm_;
    VplSampler sampler_;
    VplGather gather_;
    Buffer cache_;
    int vpls_;
    int count_ = 0;
};

} // namespace

TechniqueInfo rsmTechniqueInfo()
{
    TechniqueInfo info;
    info.name = "rsm";
    info.paper = "Nichols, Shopf & Wyman 2009 (baseline: Dachsbacher & Stamminger 2005)";
    info.lightPaths = core::LightPaths::OneBounceNoVis;
    info.passes = {
        {"rsm", "reflective shadow map of every light", ""},
        {"vpl-sample", "VPLs on a regular grid of the RSM", ""},
        {"gather", "every VPL gathered at every pixel", ""},
    };
    info.reads = {GBufferChannel::Position, GBufferChannel::Normal, GBufferChannel::Diffuse};
    info.summary = "reflective shadow map, N VPLs on a regular grid, full-screen gather at every pixel";
    info.params = {
        {"vpls", ParamType::Int, 256, 1, 6 * 1024 * 1024,
         "VPLs on a regular grid of the RSM (sqrt(vpls/views) per side of each view); gather cost is linear in it"},
    };
    for (const ParamDecl& p : rsmParams()) info.params.push_back(p);
    info.create = [](Frame&, const ParamValues& v) -> std::unique_ptr<Technique> {
        return std::make_unique<RsmGather>(rsmSettingsFrom(v), v.getInt("vpls"));
    };
    // The RSM at 64^2 (from 256^2): the same passes, a sixteenth of the VPLs and RSM texels.
    info.quickSets = {"rsmSize=64"};
    return info;
}

TechniqueInfo rsmFullTechniqueInfo()
{
    TechniqueInfo info;
    info.name = "rsm-full";
    info.paper = "Nichols, Shopf & Wyman 2009 (baseline: Dachsbacher & Stamminger 2005)";
    info.lightPaths = core::LightPaths::OneBounceNoVis;
    info.passes = {
        {"rsm", "reflective shadow map of every light", ""},
        {"vpl-sample", "VPLs on a regular grid of the RSM", ""},
        {"gather", "every VPL gathered at every pixel", ""},
    };
    info.reads = {GBufferChannel::Position, GBufferChannel::Normal, GBufferChannel::Diffuse};
    info.summary = "every RSM texel a VPL (1024^2: the paper's one-million-VPL baseline), full-screen gather; slow";
    info.params = rsmParams();
    info.create = [](Frame&, const ParamValues& v) -> std::unique_ptr<Technique> {
        const RsmSettings s = rsmSettingsFrom(v);
        // Every texel of every view a VPL of the cache: 1024^2 per view is the paper's one-million baseline.
        requireRsmSize("rsm-full", s.size, false, 1024);
        return std::make_unique<RsmGather>(s, -1);
    };
    // The RSM at 64^2 (from 256^2): the same passes, a sixteenth of the VPLs and RSM texels.
    info.quickSets = {"rsmSize=64"};
    return info;
}

} // namespace bounce::gl
