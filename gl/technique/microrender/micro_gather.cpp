#include "gl/technique/microrender/micro_gather.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "gl/gl.h"
#include "gl/technique/microrender/bindings.h"

namespace bounce::gl {

namespace {

constexpr int kWarpBins = 32;

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
    pixels_ = makeProgram(frame, hierarchy, false);
    if (atPoints) points_ = makeProgram(frame, hierarchy, true);
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
    if (settings_.rayCast) d.push_back({"RAY_CAST", "1"});
    if (settings_.rayCast && settings_.rayDiscs) d.push_back({"RAY_DISCS", "1"});
    // Even: children are queued in pairs. Two queues of 768 (the default) fit in the ray pass's 3 x 24^2 words.
    if (settings_.cutQueue > 0) d.push_back({"CUT_QUEUE", std::to_string(std::max(settings_.cutQueue, kGroup) & ~1)});
    if (!settings_.warp) d.push_back({"NO_WARP", "1"});
    if (atPoints) d.push_back({"GATHER_AT_POINTS", "1"});
    for (const Define& k : lightKindDefines(frame.gpuScene())) d.push_back(k);
    for (const Define& k : hierarchy.defines()) d.push_back(k);
    return Program::compute(atPoints ? "microrender.bounceGather" : "microrender.gather",
                            "technique/microrender/gather.comp", d);
}

void MicroGather::setUniforms(Program& program, Frame& frame, const PointCloud& cloud, const PointHierarchy& hierarchy)
{
    const core::Bounds& b = frame.gpuScene().bounds();
    const float diagonal = std::max(glm::length(b.extent()), 1e-6f);
    const float depthMax = float((1u << (32 - (hierarchy.levels() + 1))) - 2u);
    program.set("leafCount", unsigned(hierarchy.leafCount()));
    program.set("cutScale", settings_.cut);
    program.set("depthScale", depthMax / (1.01f * diagonal));
    // Half a point's disc radius: the gather point's own surface sinks under its horizon.
    program.set("gatherOffset", 0.5f * cloud.discRadius());
    program.set("warpCosSteps", int(cpuTables_.cosThetaO.size()));
    program.set("warpAlphaCount", int(cpuTables_.alphas.size()));
    for (std::size_t i = 0; i < cpuTables_.alphas.size() && i < 16; ++i)
        program.set("warpAlphas[" + std::to_string(i) + "]", cpuTables_.alphas[i]);
    setPointLightUniforms(program, frame);
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
    {
        auto t = timers.scope("gather");
        bindCommon(frame, cloud, hierarchy, caster);
        targets.bindForGather(frame, pixels_);
        setUniforms(pixels_, frame, cloud, hierarchy);
        dispatchPerTarget(pixels_, targets.count(), kGroup);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                        GL_BUFFER_UPDATE_BARRIER_BIT);
    }
    statsBuffer_.download(0, sizeof(MicroStats), &stats_);
}

void MicroGather::gatherPoints(Frame& frame, const PointCloud& cloud, const PointHierarchy& hierarchy,
                               const RayCaster& caster, int stride, Buffer& gathered, PassTimers& timers)
{
    auto t = timers.scope("bounce-gather");
    bindCommon(frame, cloud, hierarchy, caster);
    gathered.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_POINT_GATHERED);
    const int count = cloud.count() / stride;
    setUniforms(points_, frame, cloud, hierarchy);
    points_.set("gatherStride", unsigned(stride));
    points_.set("targetCount", unsigned(count));
    dispatchPerTarget(points_, count, kGroup);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

} // namespace bounce::gl
