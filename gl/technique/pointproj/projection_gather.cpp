#include "gl/technique/pointproj/projection_gather.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/point_order.h"
#include "core/point_projection.h"
#include "gl/frame/points/pixel_gather.h"
#include "gl/gl.h"
#include "gl/technique/pointproj/bindings.h"

namespace bounce::gl {

ProjectionGather::ProjectionGather(const PointCloud& cloud, const ProjectionSettings& settings, bool atPoints)
    : settings_(settings), stats_("pointproj.stats", sizeof(ProjectionStats))
{
    const int n = cloud.count();
    keyIndexBits_ = core::exactLog2(std::uint64_t(n));
    if (keyIndexBits_ < 0 || n < settings_.clusters)
        throw std::invalid_argument("point projection needs a power-of-two point count of at least the " +
                                    std::to_string(settings_.clusters) + " clusters, not " + std::to_string(n));
    if (32 - keyIndexBits_ < 8)
        throw std::invalid_argument("point projection's 32-bit (depth, point) key holds at most 2^24 points");
    texelSolidAngles_ = Buffer::fromVector("pointproj.texelSolidAngles", core::hemiOctTexelSolidAngles(kResolution));
    defines_ = cloud.defines();
    pixels_ = makeProgram(false);
    if (atPoints) points_ = makeProgram(true);
}

Program ProjectionGather::makeProgram(bool atPoints) const
{
    std::vector<Define> d = {
        {"PROJ_RES", std::to_string(kResolution)},
        {"PROJ_GROUP", std::to_string(kGroup)},
        {"CLUSTERS", std::to_string(settings_.clusters)},
        {"RANDOM_PER_CLUSTER", std::to_string(settings_.randomPerCluster)},
        {"SAMPLES", std::to_string(settings_.samples)},
        {"KEY_INDEX_BITS", std::to_string(std::max(keyIndexBits_, 1))},
        {"PROJ_MODE", std::to_string(int(settings_.mode))},
        {"SPLAT_FIXED", std::to_string(settings_.fixedSplat)},
        {"SPLAT_SHARE_DRAWN", settings_.shareDrawn ? "1" : "0"},
        {"HOLE_FILL", std::to_string(settings_.holeFill)},
    };
    if (atPoints) d.push_back({"GATHER_AT_POINTS", "1"});
    for (const Define& k : defines_) d.push_back(k);
    return Program::compute(atPoints ? "pointproj.bounceGather" : "pointproj.gather", "technique/pointproj/gather.comp",
                            d);
}

void ProjectionGather::setUniforms(Program& program, Frame& frame, const PointCloud& cloud, std::uint32_t seed)
{
    const core::Bounds& b = frame.gpuScene().bounds();
    const float diagonal = std::max(glm::length(b.extent()), 1e-6f);
    const float depthMax = float((1u << (32 - keyIndexBits_)) - 2u);
    program.set("pointCount", unsigned(cloud.count()));
    program.set("clusterSize", unsigned(cloud.count() / settings_.clusters));
    program.set("depthScale", depthMax / (1.01f * diagonal));
    program.set("gatherOffset", 0.5f * cloud.discRadius());
    program.set("frameSeed", unsigned(seed));
    cloud.bind();
    texelSolidAngles_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PROJ_TEXEL_SOLID_ANGLES);
    stats_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PROJ_STATS);
}

void ProjectionGather::gatherPixels(Frame& frame, AdaptivePixels& pixels, int count, const PointCloud& cloud,
                                    std::uint32_t seed, PassTimers& timers)
{
    auto t = timers.scope("gather");
    pixels.bindForGather(frame, pixels_);
    setUniforms(pixels_, frame, cloud, seed);
    dispatchPerTarget(pixels_, count, kGroup);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void ProjectionGather::gatherPoints(Frame& frame, const PointCloud& cloud, int stride, Buffer& gathered,
                                    std::uint32_t seed, PassTimers& timers)
{
    auto t = timers.scope("bounce-gather");
    const int count = cloud.count() / stride;
    setUniforms(points_, frame, cloud, seed);
    gathered.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_POINT_GATHERED);
    points_.set("gatherStride", unsigned(stride));
    points_.set("targetCount", unsigned(count));
    dispatchPerTarget(points_, count, kGroup);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

ProjectionStats ProjectionGather::stats() const
{
    ProjectionStats s;
    stats_.download(0, sizeof(s), &s);
    return s;
}

} // namespace bounce::gl
