#include "gl/technique/pointproj/projection_gather.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/point_order.h"
#include "core/point_projection.h"
#include "gl/frame/points/pixel_gather.h"
#include "gl/frame/shader_costs.h"
#include "gl/gl.h"
#include "gl/technique/pointproj/bindings.h"

namespace bounce::gl {

namespace {

// Flops of the functions gather.comp calls per point and texel, counted from their source (common/brdf.glsl,
// technique/pointproj/projection.glsl).
constexpr double kFlopsSplat = 95;  // splat: the direction, hemiOctEncode, Eq. 5, the side, the key
constexpr double kSurfelBytes = 32; // PointSurfel

// gather.comp per gathered pixel (one work group of kGroup): the micro-buffer cleared; N_rnd random points
// of every cluster read and weighed (Eq. 4), the carry rule, N_s samples found by a binary search over the
// clusters, every point splatted (PROJ_MODE 2: every point of the cloud); HOLE_FILL passes over the
// texels; every texel resolved (its point, radiance, f cos Omega); the group's sums and the store. Keys
// count 4 bytes each (shared memory). An adaptive splat's texels are known only on the GPU: one each (the
// side rounds to 1 below 2.25 texels, as for most of 3K splats over 32 x 32 texels; SPLAT_FIXED n: n^2).
PassCost pixelWork(const ProjectionSettings& s, const PointCloud& cloud, int texels, bool atPoints)
{
    const double brdf = atPoints ? kFlopsBrdfDiffuse : kFlopsBrdfLobes;
    const double randoms = double(s.clusters) * s.randomPerCluster;
    const bool all = s.mode == ProjectionSettings::Mode::All;
    const double splats = all ? double(cloud.count()) : randoms + s.samples;
    const double splatTexels = s.fixedSplat > 0 ? double(s.fixedSplat) * s.fixedSplat : 1.0;
    PassCost w;
    w.bytesFixed = texels * 4.0 + (atPoints ? 16 : 24 + 2 * 16) + 8 * 4; // clear, G-buffer texels, store, counters
    w.flopsFixed = 6.0 * ProjectionGather::kGroup;                       // the group's sums
    if (!all) {
        w.flopsFixed += randoms * (60 + brdf + 20) + s.clusters * 30.0 + s.samples * 45.0;
        w.bytesFixed += randoms * kSurfelBytes;
        if (s.shareDrawn) w.flopsFixed += randoms * 20; // the random draws again, after the allocation
    }
    w.flopsFixed += splats * kFlopsSplat;
    w.bytesFixed += splats * (4 + kSurfelBytes + 4 + splatTexels * 4); // area, surfel, Omega_texel, keys
    w.bytesFixed += s.holeFill * texels * 8.0; // each texel's key read, a fill written (holes' neighbours left out)
    w.flopsFixed += texels * (15 + 8 + 6 + 15 + brdf + 20 + (cloud.glossy() ? kFlopsPointGlossyRadiance : 0));
    w.bytesFixed += texels * (4 + kSurfelBytes + 8 + 4 + (cloud.glossy() ? 16 : 0));
    return w;
}

// gather.comp per invocation of a pixel's group, alike for all: the target (its G-buffer texels, or its
// point's surfel read at the group's address), its frame and seed; the rest per pixel (pixelWork).
PassCost gatherCost(const ProjectionSettings& s, const PointCloud& cloud, bool atPoints, int targets)
{
    const PassCost w = pixelWork(s, cloud, ProjectionGather::kResolution * ProjectionGather::kResolution, atPoints);
    PassCost c;
    c.flops = atPoints ? 60 : 85;
    c.fetches = atPoints ? 0 : 3;
    c.uniformWords = atPoints ? 8 : 2;
    c.bytesFixed = w.bytesFixed * targets;
    c.flopsFixed = w.flopsFixed * targets;
    return c;
}

} // namespace

ProjectionGather::ProjectionGather(Frame& frame, const PointCloud& cloud, const ProjectionSettings& settings,
                                   bool atPoints)
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
    atPoints_ = atPoints;
    makePrograms(frame);
}

void ProjectionGather::followLightKinds(Frame& frame)
{
    // The hole rays light their hits with the kinds of light the scene has now.
    if (settings_.holeRays && lightKinds(frame.gpuScene()) != lightKinds_) makePrograms(frame);
}

void ProjectionGather::makePrograms(Frame& frame)
{
    lightKinds_ = lightKinds(frame.gpuScene());
    pixels_ = makeProgram(frame, false);
    if (atPoints_) points_ = makeProgram(frame, true);
}

Program ProjectionGather::makeProgram(Frame& frame, bool atPoints) const
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
    if (settings_.holeRays) {
        d.push_back({"HOLE_RAYS", "1"});
        for (const Define& k : pointLightDefines(frame)) d.push_back(k);
        for (const Define& k : frame.rayCaster().defines()) d.push_back(k);
    }
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
    if (settings_.holeRays) {
        frame.bindSceneData();
        frame.rayCaster().bind();
        frame.setDirectLightUniforms(program);
    }
    cloud.bind();
    texelSolidAngles_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PROJ_TEXEL_SOLID_ANGLES);
    stats_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PROJ_STATS);
}

void ProjectionGather::gatherPixels(Frame& frame, AdaptivePixels& pixels, int count, const PointCloud& cloud,
                                    std::uint32_t seed, PassTimers& timers)
{
    followLightKinds(frame);
    // gather.comp per invocation (the target, its frame) and per gathered pixel (pixelWork).
    auto t = timers.scope("gather", withHoleRays(gatherCost(settings_, cloud, false, count), frame, count));
    t.expectComputes(perTargetInvocations(count, kGroup));
    pixels.bindForGather(frame, pixels_);
    setUniforms(pixels_, frame, cloud, seed);
    dispatchPerTarget(pixels_, count, kGroup);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void ProjectionGather::gatherPoints(Frame& frame, const PointCloud& cloud, int stride, Buffer& gathered,
                                    std::uint32_t seed, PassTimers& timers)
{
    const int count = cloud.count() / stride;
    followLightKinds(frame);
    // gather.comp per invocation (the point, its frame) and per gathered point (pixelWork).
    auto t = timers.scope("bounce-gather", withHoleRays(gatherCost(settings_, cloud, true, count), frame, count));
    t.expectComputes(perTargetInvocations(count, kGroup));
    setUniforms(points_, frame, cloud, seed);
    gathered.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_POINT_GATHERED);
    points_.set("gatherStride", unsigned(stride));
    points_.set("targetCount", unsigned(count));
    dispatchPerTarget(points_, count, kGroup);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

PassCost ProjectionGather::withHoleRays(PassCost c, const Frame& frame, int targets) const
{
    if (!settings_.holeRays) return c;
    // Per target as many rays and hits as in the last gather's counters (none before the first): the walks,
    // the hits' light, and per ray the texel's direction, the BRDF and the sums.
    const double rays = raysPerTarget_ * targets;
    const PassCost walk = closestHitWork(frame.rayCaster(), rays),
                   shading = hitRadianceWork(frame, hitsPerTarget_ * targets);
    c.flopsFixed += walk.flopsFixed + shading.flopsFixed + rays * (40 + kFlopsBrdfLobes);
    c.fetchesFixed += shading.fetchesFixed;
    c.bytesFixed += walk.bytesFixed + shading.bytesFixed + rays * 8;
    return c;
}

ProjectionStats ProjectionGather::stats() const
{
    ProjectionStats s;
    stats_.download(0, sizeof(s), &s);
    if (s.targets > 0) {
        raysPerTarget_ = double(s.holeRays) / s.targets;
        hitsPerTarget_ = double(s.holeHits) / s.targets;
    }
    return s;
}

} // namespace bounce::gl
