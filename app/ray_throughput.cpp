#include "app/ray_throughput.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <random>
#include <thread>

#include "core/sampling.h"
#include "gl/frame/bindings.h"
#include "gl/frame/gpu_scene.h"
#include "gl/frame/ray_caster.h"
#include "gl/gl.h"
#include "ref/embree_scene.h"

namespace bounce::app {

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b)
{
    return std::chrono::duration<double>(b - a).count();
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// Closest hits of every ray with Embree on `threads` threads; returns seconds.
double castEmbree(const ref::EmbreeScene& embree, const std::vector<gl::BatchRay>& rays, int threads,
                  std::vector<std::uint32_t>& triangles)
{
    triangles.assign(rays.size(), 0xFFFFFFFFu);
    const auto start = Clock::now();
    std::vector<std::thread> workers;
    for (int w = 0; w < threads; ++w)
        workers.emplace_back([&, w] {
            std::uint64_t count = 0;
            for (std::size_t i = std::size_t(w); i < rays.size(); i += std::size_t(threads)) {
                ref::Hit hit;
                if (embree.intersect(rays[i].origin, rays[i].dir, rays[i].tMin, rays[i].tMax, hit, count))
                    triangles[i] = embree.globalTriangle(hit.mesh, hit.prim);
            }
        });
    for (std::thread& t : workers) t.join();
    return seconds(start, Clock::now());
}

RayThroughput measure(const std::string& kind, const ref::EmbreeScene& embree, const gl::RayCaster& caster,
                      gl::RayBatch& batch, const std::vector<gl::BatchRay>& rays, int threads, int repeat)
{
    RayThroughput f;
    f.kind = kind;
    f.rays = rays.size();
    std::vector<std::uint32_t> embreeTriangles;
    std::vector<double> times;
    for (int i = 0; i <= repeat; ++i) { // the first cast warms caches and is not counted
        const double s = castEmbree(embree, rays, threads, embreeTriangles);
        if (i > 0) times.push_back(s);
    }
    f.embreeRaysPerS = double(rays.size()) / median(times);

    batch.upload(rays);
    for (const gl::RayStage stage : {gl::RayStage::Compute, gl::RayStage::Fragment}) {
        times.clear();
        for (int i = 0; i <= repeat; ++i) { // cast() waits for the GPU; the first includes compilation
            const auto start = Clock::now();
            batch.cast(caster, stage, gl::kQueryClosest);
            if (i > 0) times.push_back(seconds(start, Clock::now()));
        }
        (stage == gl::RayStage::Compute ? f.computeRaysPerS : f.fragmentRaysPerS) = double(rays.size()) / median(times);
        if (stage != gl::RayStage::Compute) continue;
        const std::vector<gl::BatchResult> gpu = batch.results();
        std::size_t same = 0, hits = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            same += gpu[i].triangle == embreeTriangles[i];
            hits += embreeTriangles[i] != 0xFFFFFFFFu;
        }
        f.agreement = double(same) / double(rays.size());
        f.hitFraction = double(hits) / double(rays.size());
    }
    return f;
}

} // namespace

nlohmann::json RayThroughput::toJson() const
{
    return {{"rays", rays},
            {"embreeRaysPerS", embreeRaysPerS},
            {"gpuComputeRaysPerS", computeRaysPerS},
            {"gpuFragmentRaysPerS", fragmentRaysPerS},
            {"sameTriangle", agreement},
            {"hitFraction", hitFraction}};
}

RayThroughput RayThroughput::fromJson(const std::string& kind, const nlohmann::json& j)
{
    RayThroughput f;
    f.kind = kind;
    f.rays = j.at("rays");
    f.embreeRaysPerS = j.at("embreeRaysPerS");
    f.computeRaysPerS = j.at("gpuComputeRaysPerS");
    f.fragmentRaysPerS = j.at("gpuFragmentRaysPerS");
    f.agreement = j.at("sameTriangle");
    f.hitFraction = j.at("hitFraction");
    return f;
}

std::vector<RayThroughput> measureRayThroughput(const core::Scene& scene, int requested, int repeat, int threads)
{
    if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    const ref::EmbreeScene embree(scene);
    const gl::RayCaster caster(scene);
    gl::RayBatch batch(caster.defines());
    // Alpha masks: the GPU walk reads materials, uvs and textures, as Embree's filter does (raycast.glsl).
    std::optional<gl::GpuScene> maskData;
    if (caster.hasAlphaMask()) {
        maskData.emplace(scene);
        maskData->materials().bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MATERIALS);
        maskData->bindGeometry();
    }

    // Coherent: the camera's primary rays of a side x side image.
    const int side = std::max(1, int(std::lround(std::sqrt(double(requested)))));
    std::vector<gl::BatchRay> primary;
    primary.reserve(std::size_t(side) * side);
    const core::Camera& cam = scene.camera;
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
            primary.push_back(
                {cam.position, 0.0f, cam.rayDirection(float(x) + 0.5f, float(y) + 0.5f, side, side), 1e30f});

    // Incoherent: from each primary hit, a cosine-distributed direction about the surface's normal
    // (rays that missed leave the camera in a random direction instead).
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    std::vector<gl::BatchRay> secondary;
    secondary.reserve(primary.size());
    std::uint64_t count = 0;
    for (const gl::BatchRay& r : primary) {
        ref::Hit hit;
        gl::BatchRay s{cam.position, 0.0f, core::sampleUniformSphere({u01(rng), u01(rng)}), 1e30f};
        if (embree.intersect(r.origin, r.dir, r.tMin, r.tMax, hit, count)) {
            const ref::SurfacePoint sp = embree.surface(hit);
            const glm::vec3 n = glm::dot(sp.ng, r.dir) < 0.0f ? sp.ng : -sp.ng;
            s.origin = sp.p;
            s.tMin = 1e-4f * std::max(1.0f, glm::length(sp.p));
            s.dir = core::Frame::fromNormal(n).toWorld(core::sampleCosineHemisphere({u01(rng), u01(rng)}));
        }
        secondary.push_back(s);
    }

    return {measure("coherent", embree, caster, batch, primary, threads, repeat),
            measure("incoherent", embree, caster, batch, secondary, threads, repeat)};
}

} // namespace bounce::app
