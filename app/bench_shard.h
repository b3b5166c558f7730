// A bench run split over machines: each shard runs its share of the config's tasks (app/bench_tasks.h) into
// a folder all shards share, and the merge writes from their records what a one-machine run writes.
//
// DIR/manifest.json   the config (as written and as the report needs it), the task list, the source hash
// DIR/tasks/ID.json   one record per finished task: the source hash, host, GL renderer and driver, and
//                     the render's row; written atomically after the task's images, so that a record
//                     means a whole task
// DIR/images/         the rows' and references' images, each moved in whole (rename) from the task's
//                     staging folder DIR/staging/ID.HOST.PID
//
// A task whose record holds this build's source hash is skipped (a resubmitted array resumes); a record
// of other sources is run again.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "app/bench_config.h"
#include "app/bench_tasks.h"

namespace bounce::app {

struct ShardRun {
    std::string configPath; // as given: the manifest records the file's text
    bool full = false;
    std::filesystem::path out;
    Shard shard;
    std::string backend = "egl";
    bool roofline = false;
};

// Runs the shard's tasks of `config` into run.out. Throws UsageError before writing anything when run.out
// holds the manifest of another task list. Returns 0, or 1 when a render wrote NaN/Inf.
int runBenchShard(const BenchConfig& config, const ShardRun& run);

// `bounce bench --merge DIR... --out OUT`: every record of the DIRs into OUT's results.csv, results.json,
// report.md, report.html, images and plots. A task without a record of the manifest's source hash is
// named in report.md and on stderr and makes it return 1. Throws UsageError (nothing written) when a DIR
// has no manifest or the DIRs hold different task lists or sources.
int mergeBenchShards(const std::vector<std::filesystem::path>& dirs, const std::filesystem::path& out);

} // namespace bounce::app
