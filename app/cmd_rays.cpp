// bounce rays: the GPU ray caster (gl/frame/ray_caster.h, glsl/common/raycast.glsl) against Embree on
// the same rays and the same scene, in rays per second. Coherent rays are the camera's primary rays;
// incoherent rays leave the surfaces those rays hit in cosine-distributed directions, as a final
// gather or a photon bounce does. Embree runs on --threads CPU threads (the path tracer's single-ray
// queries, rtcIntersect1); the GPU casts the same batch from a compute and from a fragment shader.
// On llvmpipe both run on the same CPU cores, so the ratio says how far the GLSL walk is from
// Embree's; on a GPU the GPU figures are the GPU's.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <thread>

#include "app/commands.h"
#include "app/options.h"
#include "app/render_job.h"
#include "core/image.h"
#include "core/sampling.h"
#include "gl/frame/ray_caster.h"
#include "ref/embree_scene.h"

namespace bounce::app {

namespace {

const char* kUsage =
    "usage: bounce rays [--scene NAME|PATH] [--rays N] [--repeat N] [--threads N] [--json FILE]\n"
    "                   [--backend egl|osmesa]\n"
    "\n"
    "Casts the same closest-hit rays with the GPU ray caster (compute and fragment shaders) and with\n"
    "Embree (the ground truth's ray tracer) and prints rays per second for coherent rays (the camera's\n"
    "primary rays) and incoherent rays (cosine-distributed from the surfaces those rays hit), and how\n"
    "often the two found the same triangle.\n"
    "\n"
    "  --scene    built-in name, .gltf/.glb path or scene setup        [cornell-area]\n"
    "  --rays     rays per batch (the primary rays of a square image)  [262144]\n"
    "  --repeat   timed casts of each batch; the median is reported   [3]\n"
    "  --threads  Embree's CPU threads, 0 = all cores                   [0]\n"
    "  --json     also write the figures as JSON here\n"
    "  --backend  egl (GPU when present) or osmesa                      [egl]\n";

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

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

struct Figures {
    std::string kind;
    double embreeRaysPerS = 0.0, computeRaysPerS = 0.0, fragmentRaysPerS = 0.0;
    double agreement = 0.0; // fraction of rays where the GPU (compute) and Embree found the same triangle
    double hitFraction = 0.0;
};

Figures measure(const std::string& kind, const ref::EmbreeScene& embree, const gl::RayCaster& caster,
                gl::RayBatch& batch, const std::vector<gl::BatchRay>& rays, int threads, int repeat)
{
    Figures f;
    f.kind = kind;
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

int cmdRays(const Args& args)
{
    const Options o(args, {{"scene"}, {"rays"}, {"repeat"}, {"threads"}, {"json"}, {"backend"}}, kUsage);
    if (o.helpRequested()) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (!o.positional().empty()) throw UsageError("unexpected argument '" + o.positional()[0] + "'\n\n" + kUsage);
    const int requested = o.getInt("rays", 262144, 1, 1 << 24);
    const int repeat = o.getInt("repeat", 3, 1, 100);
    int threads = o.getInt("threads", 0, 0, 4096);
    if (threads == 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    const std::string sceneArg = o.get("scene", "cornell-area");
    if (o.has("json")) {
        try {
            core::checkOutputPath(o.get("json"));
        } catch (const core::ImageError& e) {
            throw UsageError(e.what());
        }
    }
    const core::Scene scene = loadSceneForCli(sceneArg);
    auto context = createContextForCli(o.get("backend", "egl"));
    std::printf("GL renderer: %s (%s)\n", context->info().renderer.c_str(), context->info().platform.c_str());

    const ref::EmbreeScene embree(scene);
    const gl::RayCaster caster(scene);
    gl::RayBatch batch;
    std::printf("%s: %zu triangles, BVH of %zu nodes (%.1f MiB on the GPU); Embree on %d threads\n", sceneArg.c_str(),
                scene.triangleCount(), caster.bvh().nodeCount(), double(caster.bytes()) / (1 << 20), threads);

    // Coherent: the camera's primary rays of a side x side image.
    const int side = std::max(1, int(std::lround(std::sqrt(double(requested)))));
    std::vector<gl::BatchRay> primary;
    primary.reserve(std::size_t(side) * side);
    const core::Camera& cam = scene.camera;
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
            primary.push_back({cam.position, 0.0f, cam.rayDirection(float(x) + 0.5f, float(y) + 0.5f, side, side),
                               1e30f});

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

    const std::vector<Figures> figures = {measure("coherent", embree, caster, batch, primary, threads, repeat),
                                          measure("incoherent", embree, caster, batch, secondary, threads, repeat)};
    std::printf("\n%-11s %10s %14s %14s %16s %16s %10s %9s\n", "rays", "count", "Embree Mray/s", "GPU cs Mray/s",
                "GPU fs Mray/s", "Embree / GPU cs", "same tri", "hits");
    nlohmann::json j = {{"scene", sceneArg},
                        {"triangles", scene.triangleCount()},
                        {"bvhNodes", caster.bvh().nodeCount()},
                        {"renderer", context->info().renderer},
                        {"embreeThreads", threads},
                        {"rays", primary.size()},
                        {"repeat", repeat}};
    for (const Figures& f : figures) {
        std::printf("%-11s %10zu %14.2f %14.2f %16.2f %16.2f %9.2f%% %8.1f%%\n", f.kind.c_str(), primary.size(),
                    f.embreeRaysPerS * 1e-6, f.computeRaysPerS * 1e-6, f.fragmentRaysPerS * 1e-6,
                    f.embreeRaysPerS / f.computeRaysPerS, 100.0 * f.agreement, 100.0 * f.hitFraction);
        j[f.kind] = {{"embreeRaysPerS", f.embreeRaysPerS},
                     {"gpuComputeRaysPerS", f.computeRaysPerS},
                     {"gpuFragmentRaysPerS", f.fragmentRaysPerS},
                     {"sameTriangle", f.agreement},
                     {"hitFraction", f.hitFraction}};
    }
    if (o.has("json")) core::writeFileAtomic(o.get("json"), j.dump(2) + "\n");
    return 0;
}

} // namespace bounce::app
