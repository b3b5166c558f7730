#include "gl/technique/isr/multires_technique.h"

#include <algorithm>

#include "gl/frame/rsm.h"
#include "gl/technique/isr/multires_gather.h"
#include "gl/technique/isr/vpl_gather.h"
#include "gl/technique/isr/vpl_sample.h"

namespace bounce::gl {

namespace {

// rsm's regular-grid VPLs into the multiresolution buffer: by the one-pass stencil and the stenciled
// gather of §3.2 (multires-gather), or by [NW09]'s iterative refinement and per-VPL splatting that §3.2
// replaces (multires-splat, the other half of the paper's Table 1). Same VPLs, same buffer, same upsampling.
class MultiresTechnique final : public Technique {
public:
    MultiresTechnique(Frame& frame, const RsmSettings& rsm, int vpls, const MultiresSettings& multires, bool splat,
                      bool gatherAsFragments)
        : rsm_(rsm), vpls_(vpls), gather_(frame, multires, gatherAsFragments), splat_(splat)
    {}

    void render(Frame& frame, PassTimers& timers) override
    {
        rsm_.render(frame, timers);
        const int side = VplSampler::sideFor(vpls_, rsm_.viewCount(), rsm_.size());
        reserveVplCache(cache_, side * side * std::max(rsm_.viewCount(), 1));
        count_ = sampler_.sample(rsm_, cache_, side, timers);
        if (!splat_) {
            gather_.run(frame, cache_, count_, timers);
            return;
        }
        gather_.buildPyramid(frame, timers);
        points_ = gather_.refine(frame, timers);
        gather_.splat(frame, cache_, count_, timers);
        gather_.upsample(frame, timers);
    }

    void setUniforms(const ParamValues& values) override { gather_.setThresholds(values); }

    std::vector<Counter> counters() const override
    {
        std::vector<Counter> c{{"vpls", double(count_)}};
        for (const Counter& f : gather_.counters()) c.push_back(f);
        if (splat_) c.push_back({"splat.points", double(points_) * double(count_)});
        return c;
    }

private:
    RsmPass rsm_;
    VplSampler sampler_;
    Buffer cache_;
    int vpls_;
    MultiresGather gather_;
    bool splat_;
    int count_ = 0, points_ = 0;
};

std::vector<ParamDecl> multiresTechniqueParams()
{
    std::vector<ParamDecl> p = {
        {"vpls", ParamType::Int, 256, 1, 1024 * 1024,
         "VPLs on a regular grid of the RSM (as rsm); gather cost is linear in it"},
    };
    for (const ParamDecl& d : rsmParams()) p.push_back(d);
    for (const ParamDecl& d : multiresParams()) p.push_back(d);
    return p;
}

std::unique_ptr<Technique> createMultires(Frame& frame, const ParamValues& v, bool splat)
{
    // Splatting gathers nothing: its buffer is filled by points, whatever the gather's form.
    const bool asFragments = splat || MultiresGather::gatherAsFragmentsFrom(v, multiresGatherTechniqueInfo().params);
    return std::make_unique<MultiresTechnique>(frame, rsmSettingsFrom(v), v.getInt("vpls"), multiresSettingsFrom(v),
                                               splat, asFragments);
}

} // namespace

TechniqueInfo multiresGatherTechniqueInfo()
{
    TechniqueInfo info;
    info.name = "multires-gather";
    info.paper = "Nichols, Shopf & Wyman 2009";
    info.lightPaths = core::LightPaths::OneBounceNoVis;
    info.passes = {
        {"rsm", "reflective shadow map of every light", ""},
        {"vpl-sample", "VPLs on a regular grid of the RSM", ""},
        {"minmax-mipmap", "eye-space min-max pyramid of depth and normals", ""},
        {"stencil-setup", "one-pass multiresolution stencil: each patch marked at its level", ""},
        {"gather", "VPLs gathered at the marked patches of every level", ""},
        {"upsample", "joint bilateral upsampling of the levels to full resolution", ""},
    };
    info.reads = {GBufferChannel::Position, GBufferChannel::Normal, GBufferChannel::Diffuse};
    info.summary = "rsm's regular-grid VPLs gathered at multiresolution eye-space patches chosen by a one-pass stencil";
    info.params = multiresTechniqueParams();
    info.params.push_back(MultiresGather::gatherFormParam());
    info.create = [](Frame& frame, const ParamValues& v) { return createMultires(frame, v, false); };
    // The RSM at 64^2 (from 256^2): the same passes, a sixteenth of the VPLs and RSM texels.
    info.quickSets = {"rsmSize=64"};
    return info;
}

TechniqueInfo multiresSplatTechniqueInfo()
{
    TechniqueInfo info;
    info.name = "multires-splat";
    info.paper = "Nichols & Wyman 2009 (the baseline of Nichols, Shopf & Wyman 2009, Table 1)";
    info.lightPaths = core::LightPaths::OneBounceNoVis;
    info.passes = {
        {"rsm", "reflective shadow map of every light", ""},
        {"vpl-sample", "VPLs on a regular grid of the RSM", ""},
        {"minmax-mipmap", "eye-space min-max pyramid of depth and normals", ""},
        {"refine", "iterative patch refinement, one compute pass per level", ""},
        {"splat", "every VPL splatted into every patch", ""},
        {"upsample", "joint bilateral upsampling of the levels to full resolution", ""},
    };
    info.reads = {GBufferChannel::Position, GBufferChannel::Normal, GBufferChannel::Diffuse};
    info.summary = "multiresolution splatting: the same patches found by iterative refinement, every VPL splatted "
                   "to them as points (what the stencil and the gather replace)";
    info.params = multiresTechniqueParams();
    info.create = [](Frame& frame, const ParamValues& v) { return createMultires(frame, v, true); };
    // The RSM at 64^2 (from 256^2): the same passes, a sixteenth of the VPLs and RSM texels.
    info.quickSets = {"rsmSize=64"};
    return info;
}

} // namespace bounce::gl
