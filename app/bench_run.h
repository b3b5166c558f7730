// The render sweep of `bounce bench`: every setting of the config on every scene it runs on, timed,
// compared with the cached references (the technique's own light paths, `full`, "compareTo") and with
// its baseline technique, and, when asked, measured for temporal coherence.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench_config.h"
#include "app/bench_tasks.h"
#include "gl/context/context.h"

namespace bounce::app {

// One render's figures. NaN where a figure does not apply (no baseline, no temporal frames).
struct BenchRow {
    std::string scene, technique, settings, size, lightPaths;
    std::string baseline; // "technique k=v..." or "" when none
    std::string passes;   // "pass=ms;pass=ms..." (median GPU ms)
    double totalMs = 0.0;
    double relRmseOwn = 0.0, relRmseFull = 0.0, rmseOwn = 0.0, ssimOwn = 0.0;
    double relRmseBaseline = 0.0, flicker = 0.0;
    // The frame's own direct light under the same frame parameters and frame count (`direct` rendered
    // alike) against the `direct` reference: no technique can be closer to `full` than this lets it be.
    double relRmseDirectLight = 0.0;
    std::vector<double> relRmseCompareTo; // one per config.compareTo
    // NaN/Inf values in the rendered image: when there are any, every error figure is +inf (SSIM 0), in
    // the CSV, the JSON and the report, whatever the emitter mask or the downsampling would hide.
    std::size_t nonFiniteValues = 0;
    nlohmann::json record; // runRecord() + settings, size, error, baseline, temporal
};

// A render whose image holds NaN/Inf values failed: sets every error figure of the row and its record to
// +inf (SSIM 0), also where the emitter mask or the downsampling would have hidden the bad values.
void markNonFinite(BenchRow& row);

// Renders the sweep, scene by scene in the config's order (references are rendered or read from the
// cache as they are first needed). Needs a current GL context. `afterRow`, when given, sees the rows so
// far after each one (so that a run cut off by a time limit leaves what it measured). With `out`, every
// row's image and every reference go to out/images/ (app/bench_images.h), named in the records ("image",
// "references"), for report.html.
std::vector<BenchRow> runBenchmark(const BenchConfig& config, const gl::ContextInfo& context,
                                   const std::function<void(const std::vector<BenchRow>&)>& afterRow = {},
                                   const std::filesystem::path& out = {});

// One render or path-tracer task of app/bench_tasks.h alone (with its own cache of references and
// baselines): the row a one-machine run makes at the task's index, its images under out/images/.
BenchRow runTaskRow(const BenchConfig& config, const BenchTask& task, const gl::ContextInfo& context,
                    const std::filesystem::path& out);

// This machine's host name ("unknown" when it has none), recorded with every row.
std::string hostName();

} // namespace bounce::app
