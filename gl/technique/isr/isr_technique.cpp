#include "gl/technique/isr/isr_technique.h"

#include <algorithm>
#include <memory>
#include <string>

#include "gl/frame/rsm.h"
#include "gl/technique/isr/isr_cluster.h"
#include "gl/technique/isr/multires_gather.h"
#include "gl/technique/isr/multires_technique.h"
#include "gl/technique/isr/vpl_gather.h"
#include "gl/technique/isr/vpl_sample.h"

namespace bounce::gl {

namespace {

class Isr final : public Technique {
public:
    // multires: gather with the stenciled multiresolution gather of §3.2 (the paper's ISR); otherwise at
    // every pixel (for measuring what the multiresolution gather costs in error).
    Isr(Frame& frame, const RsmSettings& rsm, const IsrClusterSettings& cluster, const MultiresSettings* multires,
        bool gatherAsFragments)
        : rsm_(rsm), settings_(cluster)
    {
        if (multires)
            multires_ = std::make_unique<MultiresGather>(frame, *multires, gatherAsFragments);
        else
            gather_ = std::make_unique<VplGather>();
    }

    void render(Frame& frame, PassTimers& timers) override
    {
        rsm_.render(frame, timers);
        reserveVplCache(cache_, IsrCluster::capacity(rsm_, settings_.minLevel));
        count_ = cluster_.cluster(rsm_, cache_, settings_, timers);
        if (multires_)
            multires_->run(frame, cache_, count_, timers);
        else
            gather_->gather(frame, cache_, count_, timers);
    }

    void setUniforms(const ParamValues& values) override
    {
        settings_.depthThreshold = float(values.get("lightDepthThreshold"));
        settings_.normalThreshold = float(values.get("lightNormalThreshold"));
        if (multires_) multires_->setThresholds(values);
    }

    std::vector<Counter> counters() const override
    {
        std::vector<Counter> c{{"vpls", double(count_)}};
        const std::vector<int>& levels = cluster_.perLevel();
        for (int l = settings_.minLevel; l < int(levels.size()); ++l)
            c.push_back({"vpls.level" + std::to_string(l), double(levels[l])});
        if (multires_)
            for (const Counter& f : multires_->counters()) c.push_back(f);
        return c;
    }

private:
    RsmPass rsm_;
    IsrClusterSettings settings_;
    IsrCluster cluster_;
    std::unique_ptr<VplGather> gather_;
    std::unique_ptr<MultiresGather> multires_;
    Buffer cache_;
    int count_ = 0;
};

} // namespace

TechniqueInfo isrTechniqueInfo()
{
    TechniqueInfo info;
    info.name = "isr";
    info.paper = "Nichols, Shopf & Wyman 2009";
    info.lightPaths = core::LightPaths::OneBounceNoVis;
    info.passes = {
        {"rsm", "reflective shadow map of every light", ""},
        {"rsm-mipmap", "light-space min-max pyramid of the RSM", ""},
        {"vpl-cluster", "per-frame VPL clusters from the light-space pyramid", ""},
        {"minmax-mipmap", "eye-space min-max pyramid of depth and normals", ""},
        {"stencil-setup", "one-pass multiresolution stencil", ""},
        {"gather", "VPL clusters gathered at the marked patches", ""},
        {"upsample", "joint bilateral upsampling of the levels to full resolution", ""},
    };
    info.reads = {GBufferChannel::Position, GBufferChannel::Normal, GBufferChannel::Diffuse};
    info.summary = "image-space radiosity: per-frame multiresolution VPL clusters from light-space min-max mipmaps, "
                   "gathered at multiresolution eye-space patches";
    info.params = {
        {"lightDepthThreshold", ParamType::Float, 0.05, 0, 100,
         "light-space discontinuity: largest relative depth range (max d - min d) / min d of one VPL's patch", false,
         ParamUpdate::Uniform},
        {"lightNormalThreshold", ParamType::Float, 0.2, 0, 4,
         "light-space discontinuity: largest range of any normal component over one VPL's patch", false,
         ParamUpdate::Uniform},
        {"maxLevel", ParamType::Int, 4, 0, 11, "coarsest VPL patch: 2^maxLevel RSM texels per side"},
        {"minLevel", ParamType::Int, 2, 0, 11,
         "finest VPL patch: 2^minLevel RSM texels per side (the initial dense sampling of Fig. 7)"},
        {"multires", ParamType::Bool, 1, 0, 1,
         "gather at multiresolution eye-space patches (§3.2, the paper's ISR); 0: at every pixel"},
    };
    for (const ParamDecl& p : rsmParams()) info.params.push_back(p);
    for (const ParamDecl& p : multiresParams()) info.params.push_back(p); // eye space: as multires-gather
    info.params.push_back(MultiresGather::gatherFormParam());
    info.create = [](Frame& frame, const ParamValues& v) -> std::unique_ptr<Technique> {
        RsmSettings rsm = rsmSettingsFrom(v);
        requireRsmSize("isr", rsm.size, true); // the light-space pyramid halves it down to its coarsest level
        IsrClusterSettings c;
        int top = 0;
        while ((2 << top) <= rsm.size) ++top; // log2 of the size
        c.maxLevel = std::min(v.getInt("maxLevel"), top);
        c.minLevel = std::min(v.getInt("minLevel"), c.maxLevel);
        c.depthThreshold = float(v.get("lightDepthThreshold"));
        c.normalThreshold = float(v.get("lightNormalThreshold"));
        rsm.levels = c.maxLevel;
        const MultiresSettings multires = multiresSettingsFrom(v);
        return std::make_unique<Isr>(frame, rsm, c, v.getBool("multires") ? &multires : nullptr,
                                     MultiresGather::gatherAsFragmentsFrom(v, isrTechniqueInfo().params));
    };
    // The RSM at 64^2 (from 256^2): the same passes, a sixteenth of the VPLs and RSM texels.
    info.quickSets = {"rsmSize=64"};
    return info;
}

} // namespace bounce::gl
