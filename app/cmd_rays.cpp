// bounce rays: the GPU ray caster (gl/frame/ray_caster.h, glsl/common/raycast.glsl) against Embree on
// the same rays and the same scene, in rays per second, coherent and incoherent (what is measured and
// how: app/ray_throughput.h).
#include <algorithm>
#include <cstdio>
#include <thread>

#include "app/commands.h"
#include "app/options.h"
#include "app/ray_throughput.h"
#include "app/render_job.h"
#include "core/bvh.h"
#include "core/image.h"

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

    const core::Bvh bvh(scene);
    std::printf("%s: %zu triangles, BVH of %zu nodes; Embree on %d threads\n", sceneArg.c_str(), scene.triangleCount(),
                bvh.nodeCount(), threads);

    const std::vector<RayThroughput> figures = measureRayThroughput(scene, requested, repeat, threads);
    std::printf("\n%-11s %10s %14s %14s %16s %16s %10s %9s\n", "rays", "count", "Embree Mray/s", "GPU cs Mray/s",
                "GPU fs Mray/s", "Embree / GPU cs", "same tri", "hits");
    nlohmann::json j = {{"scene", sceneArg},
                        {"triangles", scene.triangleCount()},
                        {"bvhNodes", bvh.nodeCount()},
                        {"renderer", context->info().renderer},
                        {"embreeThreads", threads},
                        {"rays", figures[0].rays},
                        {"repeat", repeat}};
    for (const RayThroughput& f : figures) {
        std::printf("%-11s %10zu %14.2f %14.2f %16.2f %16.2f %9.2f%% %8.1f%%\n", f.kind.c_str(), f.rays,
                    f.embreeRaysPerS * 1e-6, f.computeRaysPerS * 1e-6, f.fragmentRaysPerS * 1e-6,
                    f.embreeRaysPerS / f.computeRaysPerS, 100.0 * f.agreement, 100.0 * f.hitFraction);
        j[f.kind] = f.toJson();
    }
    if (o.has("json")) core::writeFileAtomic(o.get("json"), j.dump(2) + "\n");
    return 0;
}

} // namespace bounce::app
