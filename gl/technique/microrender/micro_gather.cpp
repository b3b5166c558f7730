#include "gl/technique/microrender/micro_gather.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "gl/frame/shader_costs.h"
#include "gl/gl.h"
#include "gl/technique/microrender/bindings.h"

namespace bounce::gl {

namespace {

constexpr int kWarpBins = 32;

// Flops of the functions gather.comp calls per node, micro-pixel and ray, counted from their source
// (technique/microrender/warp.glsl, common/brdf.glsl, common/raycast.glsl).
constexpr double kFlopsWarpBin = 30;                    // warpBin: atan, sqrt, a division, bin and fraction
constexpr double kFlopsToDirection = 60;                // warpToDirection: two 5-step searches, sin, cos, sqrt
constexpr double kFlopsSolidAngle = kFlopsWarpBin + 10; // warpCosineSolidAngle

// gather.comp per gather sample (one work group), beyond what each of its invocations does alike: the
// micro-buffer cleared, the cut's nodes (read, culled or judged; the rasterised ones warped and keyed),
// the rays (direction, BVH walk, shading where they take the pixel), every micro-pixel convolved, the
// group's sums and the store; micro-buffer keys count 4 bytes each (shared memory). Nodes visited and rays
// are known only on the GPU: per sample as in the last pixel gather's counters (`last`, read back after
// it; none before the first); a ray's walk is estimated at 2 x the BVH's depth boxes and two full leaves.
PassCost sampleWork(Frame& frame, const MicroGatherSettings& s, const MicroStats& last, const PointHierarchy& hierarchy,
                    const RayCaster& caster, bool atPoints)
{
    const double pixels = double(s.resolution) * s.resolution, nodeBytes = double(hierarchy.nodeBytes());
    const bool glossy = hierarchy.nodeBytes() > sizeof(GpuMicroNode);
    const double samples = std::max<double>(last.samples, 1.0);
    PassCost w;
    w.bytesFixed = pixels * 4 + (atPoints ? 16 : 24 + 2 * 16) + 8 * 4; // clear, G-buffer texels, store, counters
    w.flopsFixed = 6.0 * MicroGather::kGroup;                          // the group's sums
    if (s.stages >= 2) { // the cut: per node visited, and per node rasterised
        w.flopsFixed += last.visited / samples * 120 + last.rasterised / samples * (kFlopsWarpBin + 20);
        w.bytesFixed += last.visited / samples * nodeBytes + last.rasterised / samples * 4;
    }
    if (s.rayCast && s.stages >= 3) {
        const double rays = last.rays / samples, taken = last.rayPixels / samples;
        w.flopsFixed += rays * (kFlopsToDirection + 20);
        w.bytesFixed += rays * 4 + taken * (12 + 4); // the pixel's key read; its radiance and key written
        if (!s.rayDiscs) {
            const PassCost walk = closestHitWork(caster, rays), shading = hitRadianceWork(frame, taken);
            w.flopsFixed += walk.flopsFixed + shading.flopsFixed;
            w.fetchesFixed += shading.fetchesFixed;
            w.bytesFixed += walk.bytesFixed + shading.bytesFixed;
        }
    }
    if (s.stages >= 4) { // the convolution, every micro-pixel
        w.flopsFixed +=
            pixels * (kFlopsToDirection + 40 + kFlopsSolidAngle + (atPoints ? kFlopsBrdfDiffuse : kFlopsBrdfLobes) +
                      (glossy ? kFlopsPointGlossyRadiance : 0));
        w.bytesFixed += pixels * (4 + nodeBytes);
    }
    return w;
}

// gather.comp per invocation, alike in a sample's group: the target (its G-buffer texels, or its point's
// surfel read at the group's address), its local frame and jitter, the GGX table's alpha search, and a 64th
// of the warp's build (16 of the 32 x 32 bins mixed from the tables, the row CDFs, the normalisation).
PassCost invocationCost(bool atPoints, std::size_t alphas)
{
    PassCost c;
    c.flops = (atPoints ? 120 : 200) + 165;
    c.fetches = atPoints ? 0 : 3;
    c.bytesRead = double(kWarpBins * kWarpBins / MicroGather::kGroup) * 4;
    c.uniformWords = atPoints ? 8 : 2 + 2.0 * double(alphas);
    return c;
}

// The whole scope: per invocation, plus per sample times the samples.
PassCost gatherCost(const PassCost& perInvocation, const PassCost& perSample, int samples)
{
    PassCost c = perInvocation;
    c.bytesFixed = perSample.bytesFixed * samples;
    c.flopsFixed = perSample.flopsFixed * samples;
    c.fetchesFixed = perSample.fetchesFixed * samples;
    return c;
}

} // namespace

MicroGather::MicroGather(Frame& frame, const MicroGatherSettings& settings, const PointHierarchy& hierarchy,
                         bool atPoints)
    : settings_(settings),
      cpuTables_(core::makeBrdfWarpTables(kWarpBins)),
      statsBuffer_("microrender.stats", sizeof(MicroStats))
{
    if (settings_.resolution != 8 && settings_.resolution != 16 && settings_.resolution != 24)
        throw std::invalid_argument("micro-buffer of " + std::to_string(settings_.resolution) + " pixels: 8, 16 or 24");
    if (hierarchy.leafCount() < kGroup)
        throw std::invalid_argument("micro-rendering needs at least " + std::to_string(kGroup) + " points");
    // Depth bits left beside the node index in the 32-bit key (§3.1 uses 8 + 24).
    if (32 - (hierarchy.levels() + 1) < 8)
        throw std::invalid_argument("micro-rendering's 32-bit micro-pixel key holds at most 2^23 points");
    tables_ = Buffer::fromVector("microrender.warpTables", cpuTables_.mass);
    atPoints_ = atPoints;
    makePrograms(frame, hierarchy);
}

void MicroGather::makePrograms(Frame& frame, const PointHierarchy& hierarchy)
{
    lightKinds_ = lightKinds(frame.gpuScene());
    pixels_ = makeProgram(frame, hierarchy, false);
    if (atPoints_) points_ = makeProgram(frame, hierarchy, true);
}

Program MicroGather::makeProgram(Frame& frame, const PointHierarchy& hierarchy, bool atPoints) const
{
    const int res = settings_.resolution;
    std::vector<Define> d = {
        {"MICRO_RES", std::to_string(res)},
        {"MICRO_GROUP", std::to_string(kGroup)},
        {"WARP_BINS", std::to_string(kWarpBins)},
        {"KEY_INDEX_BITS", std::to_string(hierarchy.levels() + 1)},
        {"LIST_CAP", std::to_string(res * res)}, // §3.1: "the post-traversal list of the same size"
        {"MICRO_STAGES", std::to_string(settings_.stages)},
    };
    if (settings_.rayCast) {
        d.push_back({"RAY_CAST", "1"});
        // Rays pass through the holes of alpha masks (raycast.glsl), as the path tracer's do.
        for (const Define& k : frame.gpuScene().alphaMaskDefines()) d.push_back(k);
    }
    if (settings_.rayCast && settings_.rayDiscs) d.push_back({"RAY_DISCS", "1"});
    if (settings_.rayCast && !settings_.rayDiscs && settings_.silhouetteRays) {
        d.push_back({"SILHOUETTE_RAYS", "1"});
        if (settings_.silhouetteDepths) d.push_back({"SILHOUETTE_DEPTHS", "1"});
    }
    // Even: children are queued in pairs. Two queues of 768 (the default) fit in the ray pass's 3 x 24^2 words.
    if (settings_.cutQueue > 0) d.push_back({"CUT_QUEUE", std::to_string(std::max(settings_.cutQueue, kGroup) & ~1)});
    if (!settings_.warp) d.push_back({"NO_WARP", "1"});
    if (atPoints) d.push_back({"GATHER_AT_POINTS", "1"});
    for (const Define& k : pointLightDefines(frame)) d.push_back(k);
    for (const Define& k : hierarchy.defines()) d.push_back(k);
    return Program::compute(atPoints ? "microrender.bounceGather" : "microrender.gather",
                            "technique/microrender/gather.comp", d);
}

void MicroGather::setUniforms(Program& program, Frame& frame, const PointHierarchy& hierarchy)
{
    const core::Bounds& b = frame.gpuScene().bounds();
    const float diagonal = std::max(glm::length(b.extent()), 1e-6f);
    const float depthMax = float((1u << (32 - (hierarchy.levels() + 1))) - 2u);
    program.set("leafCount", unsigned(hierarchy.leafCount()));
    program.set("cutScale", settings_.cut);
    program.set("depthScale", depthMax / (1.01f * diagonal));
    program.set("warpCosSteps", int(cpuTables_.cosThetaO.size()));
    program.set("warpAlphaCount", int(cpuTables_.alphas.size()));
    for (std::size_t i = 0; i < cpuTables_.alphas.size() && i < 16; ++i)
        program.set("warpAlphas[" + std::to_string(i) + "]", cpuTables_.alphas[i]);
    frame.setDirectLightUniforms(program);
}

void MicroGather::bindCommon(Frame& frame, const PointCloud& cloud, const PointHierarchy& hierarchy,
                             const RayCaster& caster)
{
    frame.bindSceneData();
    cloud.bind();
    hierarchy.bind();
    caster.bind();
    tables_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MICRO_WARP_TABLES);
    statsBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MICRO_STATS);
}

void MicroGather::gatherPixels(Frame& frame, PixelGather& targets, const PointCloud& cloud,
                               const PointHierarchy& hierarchy, const RayCaster& caster, PassTimers& timers)
{
    statsBuffer_.clearToZero();
    // The ray-cast micro-pixels light their hits with the kinds of light the scene has now.
    if (lightKinds(frame.gpuScene()) != lightKinds_) makePrograms(frame, hierarchy);
    {
        // gather.comp per invocation (the target, its frame, a 64th of the warp) and per sample (sampleWork).
        auto t = timers.scope("gather", gatherCost(invocationCost(false, cpuTables_.alphas.size()),
                                                   sampleWork(frame, settings_, stats_, hierarchy, caster, false),
                                                   targets.count()));
        t.expectComputes(perTargetInvocations(targets.count(), kGroup));
        bindCommon(frame, cloud, hierarchy, caster);
        targets.bindForGather(frame, pixels_);
        setUniforms(pixels_, frame, hierarchy);
        dispatchPerTarget(pixels_, targets.count(), kGroup);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                        GL_BUFFER_UPDATE_BARRIER_BIT);
    }
    statsBuffer_.download(0, sizeof(MicroStats), &stats_);
}

void MicroGather::gatherPoints(Frame& frame, const PointCloud& cloud, const PointHierarchy& hierarchy,
                               const RayCaster& caster, int stride, Buffer& gathered, PassTimers& timers)
{
    const int count = cloud.count() / stride;
    if (lightKinds(frame.gpuScene()) != lightKinds_) makePrograms(frame, hierarchy);
    // gather.comp per invocation (the point, its frame, a 64th of the warp) and per sample (sampleWork).
    auto t =
        timers.scope("bounce-gather", gatherCost(invocationCost(true, 0),
                                                 sampleWork(frame, settings_, stats_, hierarchy, caster, true), count));
    t.expectComputes(perTargetInvocations(count, kGroup));
    bindCommon(frame, cloud, hierarchy, caster);
    gathered.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_POINT_GATHERED);
    setUniforms(points_, frame, hierarchy);
    points_.set("gatherStride", unsigned(stride));
    points_.set("targetCount", unsigned(count));
    dispatchPerTarget(points_, count, kGroup);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

} // namespace bounce::gl
