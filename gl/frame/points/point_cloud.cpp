#include "gl/frame/points/point_cloud.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

#include "core/point_order.h"
#include "gl/context/context.h"
#include "gl/frame/bindings.h"
#include "gl/frame/points/bindings.h"
#include "gl/frame/shader_costs.h"
#include "gl/gl.h"
#include "gl/resource/dispatch.h"

namespace bounce::gl {

namespace {

constexpr int kLocal = 64;

struct GpuSurfel {
    glm::vec3 position;
    float areaM2;
    glm::vec3 normal;
    std::uint32_t diffuse;
};
static_assert(sizeof(GpuSurfel) == 32, "point_cloud.glsl's PointSurfel");
static_assert(sizeof(GpuPointSample) == 16, "point_cloud.glsl's PointSample");

// point_light.comp per point: its surfel; per punctual light the irradiance, per emitting triangle the
// polygon form factor and extent, each with its shadow view and (r+1)^2 textureGathers of four depths
// (r: the PCF radius, 0 in still frames) and the weighted sums (a bound: every point lit by every light);
// the radiance halves out, the direct too when kept, and where glossy the lobe.
PassCost pointLightCost(const Frame& frame, bool keepDirect, bool glossy)
{
    const double punctual = frame.gpuScene().punctualLightCount();
    const double area = frame.lights().count() - punctual;
    const PassCost shadow = shadowLookupCost(frame);
    PassCost c;
    c.flops = 40 + punctual * (75 + shadow.flops) + area * (420 + shadow.flops) + (glossy ? 50 : 0);
    c.fetches = (punctual + area) * shadow.fetches;
    c.bytesRead = 32 + (glossy ? 4 : 0) + (punctual + area) * shadow.bytesRead;
    c.bytesWritten = 8 + (keepDirect ? 8 : 0) + (glossy ? 16 : 0);
    c.uniformWords =
        punctual * (16 + shadow.uniformWords) + area * (16 + 12 + shadow.uniformWords); // Light, its triangle
    return c;
}

} // namespace

std::shared_ptr<const std::vector<core::SurfacePoint>> orderedSurfacePoints(const core::Scene& scene, std::size_t count,
                                                                            std::uint64_t seed)
{
    using Key = std::tuple<std::uint64_t, std::size_t, std::uint64_t>;
    static std::mutex mutex;
    static std::map<Key, std::shared_ptr<const std::vector<core::SurfacePoint>>> cache;
    const Key key{scene.contentHash(), count, seed};
    {
        std::lock_guard<std::mutex> lock(mutex);
        const auto it = cache.find(key);
        if (it != cache.end()) return it->second;
    }
    const core::SurfacePoints sp = core::sampleSurfacePoints(scene, count, seed);
    // Every level down to single points: the complete tree of micro-rendering, whose first 9 levels are
    // point projection's clusters.
    auto ordered =
        std::make_shared<const std::vector<core::SurfacePoint>>(core::orderSurfacePoints(scene, sp.points, 64));
    std::lock_guard<std::mutex> lock(mutex);
    cache[key] = ordered;
    return ordered;
}

GpuPointSample toGpuPointSample(const core::SurfacePoint& p, double triangleAreaM2)
{
    const float b0 = p.barycentrics.x, b1 = p.barycentrics.y;
    const float share = triangleAreaM2 > 0.0 ? float(p.areaM2 / triangleAreaM2) : 0.0f;
    // core: p = b0 p0 + b1 p1 + (1 - b0 - b1) p2; scene.glsl: (1 - x - y) v0 + x v1 + y v2.
    return {p.triangle, share, glm::vec2(b1, 1.0f - b0 - b1)};
}

namespace {

// Point, spot and directional lights alone, and a frame that casts shadow rays: the points' visibility is
// one ray towards each light, as deterministic as the map and without its texel (point_light.glsl says what
// the map cost). Emitting triangles keep the moving form's cube.
std::vector<Define> pointShadowRayDefines(const Frame& frame)
{
    const GpuScene& scene = frame.gpuScene();
    if (int(scene.lights().size()) != scene.punctualLightCount()) return {};
    return frame.shadowRayDefines();
}

} // namespace

std::vector<Define> pointLightDefines(const Frame& frame)
{
    std::vector<Define> d = frame.directLightDefines(false);
    const std::vector<Define> rays = pointShadowRayDefines(frame);
    d.insert(d.end(), rays.begin(), rays.end());
    return d;
}

bool pointLightReadsShadowMaps(const Frame& frame)
{
    return !frame.gpuScene().lights().empty() && pointShadowRayDefines(frame).empty();
}

int lightKinds(const GpuScene& scene)
{
    return (scene.punctualLightCount() > 0 ? 1 : 0) | (int(scene.lights().size()) > scene.punctualLightCount() ? 2 : 0);
}

PassCost hitRadianceWork(const Frame& frame, double hits)
{
    constexpr double kHitBytes = 3 * 4 + 3 * 12 + 4 + 64; // indices, vertex normals, material index, Material
    const double punctual = frame.gpuScene().punctualLightCount();
    const PassCost lights = directLightsCost(frame, punctual, frame.lights().count() - punctual);
    PassCost w;
    w.flopsFixed = hits * (40 + lights.flops);
    w.fetchesFixed = hits * lights.fetches;
    w.bytesFixed = hits * (kHitBytes + lights.bytesRead);
    return w;
}

PointCloud::PointCloud(Frame& frame, std::size_t count, std::uint64_t seed, bool keepDirect)
    : keepDirect_(keepDirect), glossy_(frame.scene().hasGlossy())
{
    const auto points = orderedSurfacePoints(frame.scene(), count, seed);
    count_ = int(points->size());
    const std::vector<double> triangleAreas = core::triangleAreas(frame.scene());
    std::vector<GpuPointSample> gpu;
    gpu.reserve(points->size());
    for (const core::SurfacePoint& p : *points) {
        gpu.push_back(toGpuPointSample(p, triangleAreas[p.triangle]));
        totalArea_ += p.areaM2;
    }
    discRadius_ = count_ > 0 ? float(std::sqrt(totalArea_ / count_ / M_PI)) : 0.0f;
    samples_ = Buffer::fromVector("points.samples", gpu);
    surfels_ = Buffer("points.surfels", std::size_t(count_) * sizeof(GpuSurfel));
    radiance_ = Buffer("points.radiance", std::size_t(count_) * 8);
    if (keepDirect_) direct_ = Buffer("points.direct", std::size_t(count_) * 8);
    if (glossy_) glossyLobes_ = Buffer("points.glossy", std::size_t(count_) * 16);
    std::vector<Define> updateDefines = defines();
    if (frame.gpuScene().hasTextures()) updateDefines.push_back({"TEXTURES", "1"});
    update_ = Program::compute("points.update", "frame/points/point_update.comp", updateDefines);
    makeLightProgram(frame);
    if (keepDirect_) relight_ = Program::compute("points.relight", "frame/points/point_relight.comp");
}

std::vector<Define> PointCloud::defines() const
{
    if (glossy_) return {{"GLOSSY_POINTS", "1"}};
    return {};
}

void PointCloud::makeLightProgram(const Frame& frame)
{
    const GpuScene& scene = frame.gpuScene();
    std::vector<Define> d = pointLightDefines(frame);
    for (const Define& k : defines()) d.push_back(k);
    lightKinds_ = lightKinds(scene);
    if (keepDirect_) d.push_back({"KEEP_DIRECT", "1"});
    light_ = Program::compute("points.light", "frame/points/point_light.comp", d);
}

void PointCloud::bind() const
{
    samples_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_POINT_SAMPLES);
    surfels_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_POINT_SURFELS);
    radiance_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_POINT_RADIANCE);
    if (keepDirect_) direct_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_POINT_DIRECT);
    if (glossy_) glossyLobes_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_POINT_GLOSSY);
}

void PointCloud::update(Frame& frame, PassTimers& timers)
{
    // point_update.comp per point: its sample, three indices, the three vertices' positions and normals and
    // the material word, the point, unit normal, the triangle's area and BRDF parameters (materials stay in
    // cache); with textures the three uvs and one bilinear sample (a bound: every material textured); one
    // 32-byte surfel out, and where glossy the lobe's material word.
    const bool textured = frame.gpuScene().hasTextures();
    PassCost cost;
    cost.flops = 110 + (textured ? 16 : 0) + (glossy_ ? 8 : 0);
    cost.fetches = textured ? 4 : 0;
    cost.bytesRead = 16 + 3 * 4 + 3 * (12 + 12) + 4 + (textured ? 3 * 8 + 4 * 4 : 0);
    cost.bytesWritten = sizeof(GpuSurfel) + (glossy_ ? 4 : 0);
    auto t = timers.scope("point-update", cost);
    t.expectComputes(count_ == 0 ? 0.0 : computeInvocations({count_, 1, 1}, {kLocal, 1, 1}));
    if (count_ == 0) return;
    frame.bindSceneData();
    bind();
    update_.set("pointCount", unsigned(count_));
    dispatchCompute(update_, {count_, 1, 1}, {kLocal, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void PointCloud::reorder(Frame& frame, PassTimers& timers, Recluster where)
{
    const auto n = std::uint32_t(count_);
    const bool gpu = where == Recluster::Gpu || (where == Recluster::Auto && !softwareRasterizer());
    if (gpu && !median_) median_ = std::make_unique<MedianSplit>();
    {
        // Every level, as at creation: micro-rendering's complete tree, point projection's clusters its
        // first levels. The positions are the surfels' (8 floats each).
        auto t = timers.scope("recluster", gpu ? median_->work(n) : PassCost{.bytesFixed = n * (32.0 + 2 * 16)});
        if (n > 0 && gpu) {
            if (!reordered_) reordered_ = Buffer("points.samplesReordered", samples_.bytes());
            median_->order(surfels_, sizeof(GpuSurfel) / sizeof(float), n);
            median_->permute(samples_, reordered_, n);
            std::swap(samples_, reordered_);
        } else if (n > 0) {
            const std::vector<GpuSurfel> surfels = surfels_.download<GpuSurfel>();
            std::vector<glm::vec3> positions(surfels.size());
            for (std::size_t i = 0; i < surfels.size(); ++i) positions[i] = surfels[i].position;
            const std::vector<std::uint32_t> order = core::medianSplitOrder(positions, 64);
            const std::vector<GpuPointSample> samples = samples_.download<GpuPointSample>();
            std::vector<GpuPointSample> reordered(samples.size());
            for (std::size_t i = 0; i < order.size(); ++i) reordered[i] = samples[order[i]];
            samples_.update(0, reordered.size() * sizeof(GpuPointSample), reordered.data());
        }
    }
    update(frame, timers);
}

void PointCloud::light(Frame& frame, PassTimers& timers)
{
    auto t = timers.scope("point-light", pointLightCost(frame, keepDirect_, glossy_));
    t.expectComputes(count_ == 0 ? 0.0 : computeInvocations({count_, 1, 1}, {kLocal, 1, 1}));
    if (count_ == 0) return;
    const GpuScene& scene = frame.gpuScene();
    // The demo may add or remove a kind of light (setLights): the program follows, as the direct pass's.
    if (lightKinds(scene) != lightKinds_) makeLightProgram(frame);
    frame.bindSceneData();
    bind();
    light_.set("pointCount", unsigned(count_));
    frame.setDirectLightUniforms(light_);
    dispatchCompute(light_, {count_, 1, 1}, {kLocal, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void PointCloud::relight(const Buffer& gathered, int stride, PassTimers& timers)
{
    // point_relight.comp per point: its representative's gathered vec4 (one per `stride` points), its
    // diffuse word and direct halves, one multiply-add; its radiance halves out.
    PassCost cost;
    cost.flops = 20;
    cost.bytesRead = 16.0 / std::max(stride, 1) + 4 + 8;
    cost.bytesWritten = 8;
    auto t = timers.scope("relight", cost);
    t.expectComputes(count_ == 0 || !keepDirect_ ? 0.0 : computeInvocations({count_, 1, 1}, {kLocal, 1, 1}));
    if (count_ == 0 || !keepDirect_) return;
    bind();
    gathered.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_POINT_GATHERED);
    relight_.set("pointCount", unsigned(count_));
    relight_.set("stride", unsigned(stride));
    dispatchCompute(relight_, {count_, 1, 1}, {kLocal, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

} // namespace bounce::gl
