// bounce probe: this machine's ceilings (gl/probe/machine_probe.h), measured by small GL kernels and
// cached per renderer; the run records of render and bench give every pass's bound and efficiency
// against them (app/roofline.h).
#include <cstdio>

#include "app/commands.h"
#include "app/options.h"
#include "app/render_job.h"
#include "app/roofline.h"
#include "core/image.h"

namespace bounce::app {

namespace {

const char* kUsage = "usage: bounce probe [--force] [--size N] [--repeats N] [--json FILE] [--backend egl|osmesa]\n"
                     "\n"
                     "Measures what a fragment pass and a compute pass can do per second on this machine (FMA\n"
                     "throughput, texel fetches, uniform-block reads in a gather's loop, texture/framebuffer/\n"
                     "image/buffer bandwidth) and how many small\n"
                     "triangles the rasteriser sets up, with small GL kernels (glsl/probe/). The figures are\n"
                     "cached per GL renderer; render and bench then give each pass's bound (boundMs: its work at\n"
                     "these ceilings) and efficiency (bound over measured time) in their records.\n"
                     "\n"
                     "  --force    measure again even when this renderer's figures are cached\n"
                     "  --size     side of the square targets                        [1024]\n"
                     "  --repeats  timed runs per kernel (median reported)             [5]\n"
                     "  --json     also write the figures here\n"
                     "  --backend  egl (GPU when present) or osmesa                    [egl]\n";

} // namespace

int cmdProbe(const Args& args)
{
    const Options o(args, {{"force", false}, {"size"}, {"repeats"}, {"json"}, {"backend"}}, kUsage);
    if (o.helpRequested()) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (!o.positional().empty()) throw UsageError("unexpected argument '" + o.positional()[0] + "'\n\n" + kUsage);
    gl::ProbeOptions po;
    po.size = o.getInt("size", 1024, 64, 4096);
    po.repeats = o.getInt("repeats", 5, 1, 100);
    if (o.has("json")) {
        try {
            core::checkOutputPath(o.get("json"));
        } catch (const core::ImageError& e) {
            throw UsageError(e.what());
        }
    }
    auto context = createContextForCli(o.get("backend", "egl"));
    const std::string renderer = context->info().renderer;
    std::printf("GL renderer: %s (%s)\n", renderer.c_str(), context->info().platform.c_str());
    std::optional<gl::Ceilings> c;
    const bool defaults = !o.has("size") && !o.has("repeats");
    if (!o.has("force") && defaults) c = cachedCeilings(renderer);
    if (c) {
        std::printf("cached: %s\n", ceilingsCachePath(renderer).c_str());
    } else {
        po.progress = [](const std::string& kernel, int done, int total) {
            std::fprintf(stderr, "\rprobe [%-*s] %d/%d %-28s", total, std::string(done, '#').c_str(), done, total,
                         kernel.c_str());
            if (done == total) std::fputc('\n', stderr);
        };
        c = gl::probeMachine(po);
        storeCeilings(*c);
        std::printf("measured, cached in %s\n", ceilingsCachePath(renderer).c_str());
    }
    std::printf("\n%-28s %12s %12s\n", "ceiling", "fragment", "compute");
    std::printf("%-28s %12.1f %12.1f\n", "FMA GFLOP/s", c->fragmentGflops, c->computeGflops);
    std::printf("%-28s %12.2f %12.2f\n", "texel fetches G/s", c->fragmentGfetches, c->computeGfetches);
    std::printf("%-28s %12.2f %12.2f\n", "uniform-block words G/s", c->fragmentGuniformWords, c->computeGuniformWords);
    std::printf("%-28s %12.1f %12.1f\n", "texture/image GB/s", c->fragmentGBps, c->computeImageGBps);
    std::printf("%-28s %12s %12.1f\n", "buffer GB/s", "-", c->computeBufferGBps);
    std::printf("%-28s %12.1f %12s\n", "framebuffer (blend) GB/s", c->framebufferGBps, "-");
    std::printf("%-28s %12.2f %12s\n", "triangles M/s (8 px each)", c->mtrianglesPerSecond, "-");
    if (o.has("json")) {
        core::writeFileAtomic(o.get("json"), c->toJson().dump(2) + "\n");
        std::printf("wrote %s\n", o.get("json").c_str());
    }
    return 0;
}

} // namespace bounce::app
