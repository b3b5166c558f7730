#include "gl/frame/points/point_cloud.h"

#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

#include "core/point_order.h"
#include "gl/frame/bindings.h"
#include "gl/frame/points/bindings.h"
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

GpuPointSample toGpuPointSample(const core::SurfacePoint& p)
{
    const float b0 = p.barycentrics.x, b1 = p.barycentrics.y;
    // core: p = b0 p0 + b1 p1 + (1 - b0 - b1) p2; scene.glsl: (1 - x - y) v0 + x v1 + y v2.
    return {p.triangle, p.areaM2, glm::vec2(b1, 1.0f - b0 - b1)};
}

std::vector<Define> lightKindDefines(const GpuScene& scene)
{
    std::vector<Define> d;
    if (scene.punctualLightCount() > 0) d.push_back({"PUNCTUAL_LIGHTS", "1"});
    if (int(scene.lights().size()) > scene.punctualLightCount()) d.push_back({"AREA_LIGHTS", "1"});
    return d;
}

void setPointLightUniforms(Program& program, const Frame& frame)
{
    program.set("punctualLightCount", frame.gpuScene().punctualLightCount());
    program.set("lightCount", frame.shadowMaps().lightCount());
    frame.shadowMaps().setPcfUniforms(program, frame.settings().pcfRadius);
}

PointCloud::PointCloud(Frame& frame, std::size_t count, std::uint64_t seed, bool keepDirect)
    : keepDirect_(keepDirect), glossy_(frame.scene().hasGlossy())
{
    const auto points = orderedSurfacePoints(frame.scene(), count, seed);
    count_ = int(points->size());
    std::vector<GpuPointSample> gpu;
    gpu.reserve(points->size());
    for (const core::SurfacePoint& p : *points) {
        gpu.push_back(toGpuPointSample(p));
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
    makeLightProgram(frame.gpuScene());
    if (keepDirect_) relight_ = Program::compute("points.relight", "frame/points/point_relight.comp");
}

std::vector<Define> PointCloud::defines() const
{
    if (glossy_) return {{"GLOSSY_POINTS", "1"}};
    return {};
}

void PointCloud::makeLightProgram(const GpuScene& scene)
{
    std::vector<Define> d = lightKindDefines(scene);
    for (const Define& k : defines()) d.push_back(k);
    punctual_ = scene.punctualLightCount() > 0;
    area_ = int(scene.lights().size()) > scene.punctualLightCount();
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
    auto t = timers.scope("point-update");
    if (count_ == 0) return;
    frame.bindSceneData();
    bind();
    update_.set("pointCount", unsigned(count_));
    dispatchCompute(update_, {count_, 1, 1}, {kLocal, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void PointCloud::light(Frame& frame, PassTimers& timers)
{
    auto t = timers.scope("point-light");
    if (count_ == 0) return;
    const GpuScene& scene = frame.gpuScene();
    // The demo may add or remove a kind of light (setLights): the program follows, as the direct pass's.
    if (punctual_ != (scene.punctualLightCount() > 0) ||
        area_ != (int(scene.lights().size()) > scene.punctualLightCount()))
        makeLightProgram(scene);
    frame.bindSceneData();
    bind();
    light_.set("pointCount", unsigned(count_));
    setPointLightUniforms(light_, frame);
    dispatchCompute(light_, {count_, 1, 1}, {kLocal, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void PointCloud::relight(const Buffer& gathered, int stride, PassTimers& timers)
{
    auto t = timers.scope("relight");
    if (count_ == 0 || !keepDirect_) return;
    bind();
    gathered.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_POINT_GATHERED);
    relight_.set("pointCount", unsigned(count_));
    relight_.set("stride", unsigned(stride));
    dispatchCompute(relight_, {count_, 1, 1}, {kLocal, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

} // namespace bounce::gl
