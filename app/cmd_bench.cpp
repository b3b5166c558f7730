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
#include "app/bench_shard.h"
#include "app/bench_tasks.h"
#include "app/commands.h"
#include "app/options.h"
#include "app/render_job.h"
#include "app/roofline.h"

namespace bounce::app {

namespace {

const char* kUsage =
    "usage: bounce bench --config bench/NAME.json --out DIR [--backend egl|osmesa] [--cache DIR] [--full]\n"
    "                    [--shard I/N]\n"
    "       bounce bench --config bench/NAME.json --list-tasks [--full]\n"
    "       bounce bench --merge DIR... --out OUT\n"
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
    "frame with the GPU time so far (record \"curve\"), plotted in convergence.png.\n"
    "A camera-path run, {\"technique\": T, \"path\": \"bench/paths/NAME.json\", \"every\": K [10],\n"
    "\"indirectScale\": N [1], \"stillFrames\": M [0]}, renders the path one frame per step with no still\n"
    "frames, as `bounce render --path` does (no \"warmup\", \"frames\", \"curve\", \"temporalFrames\" or\n"
    "\"against\"), times every frame and compares frames iK and iK+1 with path-tracer references of the\n"
    "technique's own light paths at their own camera and lights (cached): the mean, the second half's mean\n"
    "and the worst relative RMSE, and the flicker, the mean over the pairs (iK, iK+1) of the RMS of the\n"
    "change of the error image over the references' mean (a stable bias is not flicker). With M > 0 each\n"
    "frame iK is also rendered still (M frames at its camera) for the moving / still ratio: the mean of\n"
    "the frames' ratios, and the second half's mean error over its still images' mean. report.md gives\n"
    "a table of camera paths per scene; report.html plots error and frame time over the path and plays\n"
    "the measured frames beside their references. The top-level\n"
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
    "              and DIR/roofline.png (achieved GFLOP/s against flop/byte under the ceilings)\n"
    "\n"
    "On a cluster or several machines (README, \"The study\"; scripts/slurm/):\n"
    "  --list-tasks  print the config's tasks, one per line: INDEX ID KIND SCENE TECHNIQUE PARAMS (tab-separated;\n"
    "                KIND reference, render, path-tracer or rays; ID a hash of what the task computes), references\n"
    "                first; the same config gives the same list everywhere\n"
    "  --shard I/N   run the tasks whose index modulo N is I (0 <= I < N) into DIR, which all shards share:\n"
    "                DIR/manifest.json, DIR/tasks/ID.json per task (written after its images), DIR/images/.\n"
    "                A task with a record of the same sources is skipped, so a run resubmitted resumes. Under\n"
    "                a Slurm array, without --shard: I = SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN (over the\n"
    "                step), N = SLURM_ARRAY_TASK_COUNT. The shards write no report; --merge does.\n"
    "  --merge DIR...  read every record of the DIRs and write into --out OUT what a one-machine run writes;\n"
    "                a task without a record is named in report.md and makes the merge exit with status 1;\n"
    "                rows of different GL renderers are on Pareto fronts of their own, and report.md says so\n";

} // namespace

int cmdBench(const Args& args)
{
    const Options o(args,
                    {{"config"},
                     {"out"},
                     {"backend"},
                     {"cache"},
                     {"roofline", false},
                     {"full", false},
                     {"list-tasks", false},
                     {"shard"},
                     {"merge", false}},
                    kUsage);
    if (o.helpRequested()) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (o.has("merge")) {
        if (!o.has("out") || o.positional().empty() || o.has("config") || o.has("shard") || o.has("list-tasks"))
            throw UsageError("--merge takes folders of shards and --out, nothing else\n\n" + std::string(kUsage));
        return mergeBenchShards({o.positional().begin(), o.positional().end()}, o.get("out"));
    }
    if (!o.positional().empty())
        throw UsageError("unexpected argument '" + o.positional().front() + "'\n\n" + std::string(kUsage));
    if (o.has("list-tasks")) {
        if (!o.has("config")) throw UsageError("--list-tasks needs --config\n\n" + std::string(kUsage));
        const BenchConfig config = readBenchConfig(o.get("config"), o.get("cache"), o.has("full"));
        for (const BenchTask& t : benchTasks(config)) std::printf("%s\n", taskLine(t, config).c_str());
        return 0;
    }
    if (!o.has("config") || !o.has("out"))
        throw UsageError("--config and --out are required\n\n" + std::string(kUsage));
    // Everything is checked before the first (long) render and before anything is written: the shard
    // (--shard, or the Slurm array's variables) and the config.
    Shard shard;
    const bool sharded = o.has("shard") ? (shard = parseShard(o.get("shard")), true) : slurmShard(shard);
    const BenchConfig config = readBenchConfig(o.get("config"), o.get("cache"), o.has("full"));
    if (sharded) {
        return runBenchShard(
            config, {o.get("config"), o.has("full"), o.get("out"), shard, o.get("backend", "egl"), o.has("roofline")});
    }
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
    return finishBenchReport(out, rows);
}

} // namespace bounce::app
