#include "gl/technique/isr/hisr_technique.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include "gl/frame/rsm.h"
#include "gl/gl.h"
#include "gl/technique/isr/bindings.h"
#include "gl/technique/isr/multires_gather.h"
#include "gl/technique/isr/multires_technique.h"
#include "gl/technique/isr/vpl_gather.h"
#include "gl/technique/isr/vpl_tree.h"

namespace bounce::gl {

double hisrPeakIntensity(const std::vector<LightSource>& lights)
{
    double peak = 0.0;
    std::map<int, glm::dvec3> areaLobes; // per emitting mesh: sum of L_k A_k
    for (const LightSource& l : lights) {
        if (l.type == kLightArea) {
            const double a =
                0.5 * glm::length(glm::cross(l.triangle[1] - l.triangle[0], l.triangle[2] - l.triangle[0]));
            areaLobes[l.group] += glm::dvec3(l.intensity) * a;
        } else {
            peak = std::max(peak, double(std::max({l.intensity.x, l.intensity.y, l.intensity.z})));
        }
    }
    for (const auto& [group, lobe] : areaLobes) peak = std::max(peak, std::max({lobe.x, lobe.y, lobe.z}));
    return peak;
}

int hisrGatherLanes(unsigned fragments)
{
    // 2^17 invocations: on an NVIDIA H200 at 1024x768, 4 lanes for the Cornell box's 28,310 fragments
    // gathered 2.1x faster than 1 and 1.9x faster than 16; 1 lane for Sponza's 130,626 fragments 1.5x
    // faster than 4 and 3.4x faster than 16. The first frame, with no count yet, takes 4.
    if (fragments == 0) return 4;
    int lanes = 1;
    while (lanes < 16 && std::uint64_t(fragments) * std::uint64_t(2 * lanes) <= (1u << 17)) lanes *= 2;
    return lanes;
}

double hisrRefineConstant(double peakIntensity, double tau, int rsmSize)
{
    if (tau <= 0.0) return std::numeric_limits<double>::infinity();
    return 2.0 * (peakIntensity - tau) / (3.0 * tau * double(rsmSize) * double(rsmSize)); // Eq. 8
}

namespace {

class Hisr final : public Technique {
public:
    Hisr(Frame& frame, const RsmSettings& rsm, double tau, int topGrid, float lightDepthThreshold,
         float lightNormalThreshold, int discontinuityLevel, const MultiresSettings& multires, bool gatherAsFragments,
         int gatherLanes)
        : rsm_(rsm),
          tree_(topGrid, lightDepthThreshold, lightNormalThreshold),
          tau_(tau),
          discontinuityLevel_(discontinuityLevel),
          gather_(frame, multires, gatherAsFragments),
          lanes_(gatherLanes),
          program_(
              gather_.gatherProgram("hisr.gather", "technique/isr/hisr_gather.frag", "technique/isr/hisr_gather.comp")),
          stats_("hisr.stats", 4 * sizeof(unsigned))
    {}

    void render(Frame& frame, PassTimers& timers) override
    {
        rsm_.render(frame, timers);
        tree_.build(rsm_, timers);
        gather_.buildPyramid(frame, timers);
        gather_.markValidFragments(frame, timers);
        const double T = hisrRefineConstant(hisrPeakIntensity(frame.gpuScene().lights()), tau_, rsm_.size());
        stats_.clearToZero();
        stats_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_ISR_TREE_STATS);
        tree_.bindTexels();
        tree_.setUniforms(program_);
        const int lanes = gather_.gatherAsFragments() ? 1 : lanes_ > 0 ? lanes_ : hisrGatherLanes(fragments_);
        if (!gather_.gatherAsFragments()) program_.set("lanes", lanes);
        program_.set("alwaysRefine", std::isinf(T) ? 1 : 0);
        program_.set("discontinuityLevel", discontinuityLevel_);
        program_.set("refineT", std::isinf(T) ? 0.0f : float(T));
        // Per root a fragment's walk runs at most one step per node of the subtree and one climb per node
        // it leaves as the last of four: fewer than 2 (nodes + 1) loop iterations (llvmpipe's budget).
        const int roots = tree_.rootCount();
        const long long perRoot = 2LL * (tree_.subtreeNodes() + 1);
        const int perDraw = int(std::clamp<long long>(MultiresGather::loopBudget() / perRoot, 1, std::max(roots, 1)));
        const int draws = std::max(1, (roots + perDraw - 1) / perDraw);
        // hisr_gather.frag per fragment: its patch, and per cluster gathered three tree texels and one
        // VPL's contribution (with the normal's normalisation); a walk visits about 4/3 nodes per cluster
        // gathered (every refined node has four children). The clusters per fragment are the walk's own
        // count, from the frame before (the same scene and view walk the same tree).
        PassCost cost;
        const double visited = clustersPerFragment_ * 4.0 / 3.0;
        cost.flops = (20 + clustersPerFragment_ * (kFlopsPerVpl + 12) + visited * 10) / draws;
        cost.fetches = (3 + visited * 3) / draws;
        // The tree's texels are fetches, not memory traffic: 87,296 nodes at 64 bytes (5.6 MB at rsmSize 256)
        // stay in the caches, and counting them as bytes put the bound at the bandwidth ceiling.
        cost.bytesRead = (16 + 8 + 8) / draws + 16;
        cost.bytesWritten = 16;
        gather_.gather(
            frame, program_, timers, draws,
            [&](Program& p, int i) {
                p.set("rootBegin", i * perDraw);
                p.set("rootEnd", std::min(roots, (i + 1) * perDraw));
            },
            cost, lanes);
        clustersPerFragment_ = gatheredPerFragment();
        gather_.upsample(frame, timers);
    }

    // Clusters gathered per fragment by the last gather (its SSBO_ISR_TREE_STATS counters).
    double gatheredPerFragment() const
    {
        unsigned s[4] = {0, 0, 0, 0};
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        stats_.download(0, sizeof(s), s);
        const double gathered = double(s[0]) + 4294967296.0 * double(s[1]);
        fragments_ = s[2];
        return s[2] > 0 ? gathered / double(s[2]) : 0.0;
    }

    void setUniforms(const ParamValues& values) override
    {
        tau_ = values.get("tau");
        tree_.setThresholds(float(values.get("lightDepthThreshold")), float(values.get("lightNormalThreshold")));
        gather_.setThresholds(values);
    }

    std::vector<Counter> counters() const override
    {
        std::vector<Counter> c = gather_.counters();
        unsigned s[4] = {0, 0, 0, 0};
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        stats_.download(0, sizeof(s), s);
        const double gathered = double(s[0]) + 4294967296.0 * double(s[1]);
        c.push_back({"vpl-tree.nodes", double(tree_.nodeCount())});
        c.push_back({"vpl-tree.roots", double(tree_.rootCount())});
        c.push_back({"clusters.gathered", gathered});
        c.push_back({"clusters.perFragment", s[2] > 0 ? gathered / double(s[2]) : 0.0});
        return c;
    }

private:
    RsmPass rsm_;
    VplTree tree_;
    double tau_;
    int discontinuityLevel_;
    MultiresGather gather_;
    int lanes_; // invocations per fragment of the compute form (hisr_gather.comp); 0: hisrGatherLanes
    Program program_;
    Buffer stats_;
    double clustersPerFragment_ = 0.0;
    mutable unsigned fragments_ = 0; // valid fragments of the last gather
};

} // namespace

TechniqueInfo hisrTechniqueInfo()
{
    TechniqueInfo info;
    info.name = "hisr";
    info.paper = "Nichols, Shopf & Wyman 2009";
    info.lightPaths = core::LightPaths::OneBounceNoVis;
    info.passes = {
        {"rsm", "reflective shadow map of every light", ""},
        {"vpl-tree", "the VPL tree over the full RSM", ""},
        {"minmax-mipmap", "eye-space min-max pyramid of depth and normals", ""},
        {"stencil-setup", "one-pass multiresolution stencil", ""},
        {"gather", "per-fragment walk of the VPL tree", ""},
        {"upsample", "joint bilateral upsampling of the levels to full resolution", ""},
    };
    info.reads = {GBufferChannel::Position, GBufferChannel::Normal, GBufferChannel::Diffuse};
    info.summary = "hierarchical image-space radiosity: per-fragment VPL clusters from a VPL tree of the full RSM";
    info.params = {
        {"tau", ParamType::Float, 1e-4, 0, 1e30,
         "Eq. 8 error threshold tau (W/sr, as the light's intensity I): larger, coarser clusters; 0: every texel "
         "(rsm-full)",
         false, ParamUpdate::Uniform},
        {"topGrid", ParamType::Int, 16, 1, 1024,
         "top patches per side of each view where the traversal starts, a power of two (the paper: 16)", true},
        {"lightDepthThreshold", ParamType::Float, 0.1, 0, 1e30,
         "departure: clusters whose relative light-distance range exceeds this are always refined; 1e30: the paper",
         false, ParamUpdate::Uniform},
        {"lightNormalThreshold", ParamType::Float, 0.01, 0, 1e30,
         "departure: clusters with 1 - |mean unit normal| above this are always refined; 1e30: the paper", false,
         ParamUpdate::Uniform},
        {"lightRefineLevel", ParamType::Int, kAutoValue, 0, VplTree::kMaxDepth,
         "departure: clusters spanning a light-space discontinuity are always refined down to this level; auto: "
         "log2(rsmSize / 128)"},
    };
    info.params.back().allowAuto = true;
    info.params.push_back(MultiresGather::gatherFormParam());
    info.params.push_back(choiceParam(
        "gatherLanes", {"auto", "1", "4", "16", "64"}, 0,
        "compute gather: invocations that share one fragment, each walking every n-th top patch; auto: enough to "
        "fill a GPU with the last frame's valid fragments (2^17 invocations, at most 16 per fragment)"));
    for (const ParamDecl& p : rsmParams()) info.params.push_back(p);
    for (const ParamDecl& p : multiresParams()) info.params.push_back(p);
    info.create = [](Frame& frame, const ParamValues& v) -> std::unique_ptr<Technique> {
        RsmSettings rsm = rsmSettingsFrom(v);
        requireRsmSize("hisr", rsm.size, true, 1024); // the VPL tree is a quadtree over each view
        int level = v.isAuto("lightRefineLevel") ? -1 : v.getInt("lightRefineLevel");
        if (level < 0) level = std::max(0, int(std::bit_width(unsigned(rsm.size))) - 8); // log2(size / 128)
        const bool asFragments = MultiresGather::gatherAsFragmentsFrom(v, hisrTechniqueInfo().params);
        const std::string lanes = v.getChoice(hisrTechniqueInfo().params, "gatherLanes");
        return std::make_unique<Hisr>(frame, rsm, v.get("tau"), v.getInt("topGrid"),
                                      float(v.get("lightDepthThreshold")), float(v.get("lightNormalThreshold")), level,
                                      multiresSettingsFrom(v), asFragments, lanes == "auto" ? 0 : std::stoi(lanes));
    };
    // The RSM at 64^2 (from 256^2): the same passes, a sixteenth of the VPLs and RSM texels.
    info.quickSets = {"rsmSize=64"};
    return info;
}

} // namespace bounce::gl
