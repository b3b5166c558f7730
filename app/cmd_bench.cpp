// bounce bench: scenes x techniques x parameter settings, each rendered with timer queries (warm-up
// frames, then the median and spread of the timed frames) and compared with the cached ground truth of
// the technique's own light paths and of `full`. The config is read and checked first
// (app/bench_config.*), then the sweep runs (app/bench_run.*), then the files are written
// (app/bench_report.*): results.csv, results.json, report.md and speed_error.png in --out.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "app/bench_config.h"
#include "app/bench_report.h"
#include "app/bench_roofline.h"
#include "app/bench_run.h"
#include "app/commands.h"
#include "app/options.h"
#include "app/render_job.h"
#include "app/roofline.h"

namespace bounce::app {

namespace {

const char* kUsage =
    "usage: bounce bench --config bench/NAME.json --out DIR [--backend egl|osmesa] [--cache DIR] [--full]\n"
    "\n"
    "For each scene x technique x parameter setting of the config: render (warm-up frames, then timed\n"
    "frames: median, min, max GPU ms per pass), compare with the cached references (the technique's own\n"
    "light paths and `full`), and write DIR/results.csv, DIR/results.json, DIR/report.md and\n"
    "DIR/speed_error.png (time against relative RMSE, log scales, Pareto front marked), and DIR/report.html:\n"
    "the same figures as a page that opens from disk with no network (speed against error per scene, every\n"
    "image beside the references in a viewer with flip, split, exposure, zoom and an error map, each run's\n"
    "passes, counters, memory and the command that reproduces it), with its images under DIR/images/.\n"
    "\n"
    "Config: {\"size\": \"WxH\", \"warmup\": N, \"frames\": N, \"reference\": {\"spp\": N} | {\"noise\": X} [+ "
    "\"size\"],\n"
    "         \"scenes\": [...], \"runs\": [{\"technique\": T, \"set\": {k: v}, \"sweep\": {k: [v...]}}]}\n"
    "A sweep is the cartesian product of its lists. A run may also name \"against\": {\"technique\": T,\n"
    "\"set\": {...}} (relative RMSE of the indirect light against it, e.g. full-resolution gathering) and\n"
    "\"temporalFrames\": N (the light moves along a fixed circle; mean frame-to-frame difference of the\n"
    "indirect light). A run may override \"size\", \"warmup\" and \"frames\" and restrict \"scenes\";\n"
    "\"curve\": true records, for a progressive technique, the relative RMSE against `full` after every timed\n"
    "frame with the GPU time so far (record \"curve\"), plotted in convergence.png. The top-level\n"
    "\"pathTracerSpp\": [N...] adds rows\n"
    "\"path-tracer\" (`full` at N spp, the reference's size, timed) for time against error beside it.\n"
    "The top-level \"compareTo\": [paths...] adds references beyond the technique's own and `full` (e.g.\n"
    "\"onebounce\"). A reference \"size\" that divides every run's size compares box-downsampled images\n"
    "against references of that size: less noise for the same cost. The top-level \"rays\": N also casts N\n"
    "rays per scene with the GPU ray caster and with Embree (coherent and incoherent, as `bounce rays`) into\n"
    "a table of report.md and DIR/rays.json. Timings compare only within one run.\n"
    "\n"
    "  --full      also the runs marked \"full\": true and the scenes of the top-level \"fullScenes\"\n"
    "              (bench/study.json: the default run is the quick study, --full all of it)\n"
    "  --roofline  measure this machine's ceilings first when they are not cached (bounce probe); with\n"
    "              cached ceilings report.md gives every pass's bound and efficiency, and DIR/roofline.csv\n"
    "              and DIR/roofline.png (achieved GFLOP/s against flop/byte under the ceilings)\n";

} // namespace

int cmdBench(const Args& args)
{
    const Options o(args, {{"config"}, {"out"}, {"backend"}, {"cache"}, {"roofline", false}, {"full", false}}, kUsage);
    if (o.helpRequested()) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (!o.has("config") || !o.has("out"))
        throw UsageError("--config and --out are required\n\n" + std::string(kUsage));
    // Everything is checked before the first (long) render and before anything is written.
    const BenchConfig config = readBenchConfig(o.get("config"), o.get("cache"), o.has("full"));
    const std::filesystem::path out = o.get("out");
    std::filesystem::create_directories(out);
    auto context = createContextForCli(o.get("backend", "egl"));
    std::printf("GL renderer: %s (%s)\n", context->info().renderer.c_str(), context->info().platform.c_str());
    if (o.has("roofline") && !cachedCeilings(context->info().renderer)) {
        std::printf("measuring this machine's ceilings (bounce probe), once per renderer\n");
        measureCeilings();
    }
    // The tables are rewritten after every render: a run stopped part way (a time limit on a lent GPU
    // machine, Ctrl-C) leaves results.json, results.csv and report.md of the renders it finished.
    const std::vector<BenchRow> rows = runBenchmark(
        config, context->info(),
        [&](const std::vector<BenchRow>& done) { writeBenchReport(out, config, done, {}, context->info()); }, out);
    std::vector<SceneRays> rays;
    if (config.rays > 0)
        for (std::size_t i = 0; i < config.scenes.size(); ++i) {
            std::printf("ray casting on %s: %d rays, GPU and Embree\n", config.sceneNames[i].c_str(), config.rays);
            rays.push_back({config.sceneNames[i], measureRayThroughput(config.scenes[i], config.rays, 3, 0)});
        }
    writeBenchReport(out, config, rows, rays, context->info());
    int rc = plotSpeedError(out);
    std::printf("wrote %s/{results.csv,results.json,report.md,report.html%s}\n", out.string().c_str(),
                rc == 0 ? ",speed_error.png" : "; not speed_error.png: the plot script failed");
    if (std::any_of(rows.begin(), rows.end(), [](const BenchRow& r) { return r.record.contains("curve"); })) {
        rc |= plotConvergence(out);
        std::printf("wrote %s/convergence.png: the curves' error against time and steps, beside the path tracer\n",
                    out.string().c_str());
    }
    if (hasRoofline(rows)) {
        rc |= plotRoofline(out);
        std::printf("wrote %s/{roofline.csv,roofline.png}: every pass against its bound\n", out.string().c_str());
    }
    std::size_t failed = 0;
    for (const BenchRow& r : rows)
        if (r.nonFiniteValues > 0) {
            std::fprintf(stderr, "bounce bench: error: %s (%s) on %s wrote %zu NaN/Inf values\n", r.technique.c_str(),
                         r.settings.c_str(), r.scene.c_str(), r.nonFiniteValues);
            ++failed;
        }
    return rc == 0 && failed == 0 ? 0 : 1;
}

} // namespace bounce::app
