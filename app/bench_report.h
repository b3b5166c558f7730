// What `bounce bench` writes: results.csv (one row per render, the plot's input), results.json (the
// runs' full records), report.md (one table per scene, then the per-pass breakdown like the papers'
// tables), speed_error.png (bench/plot_speed_error.py, matplotlib) and report.html (bench/report/).
#pragma once

#include <filesystem>
#include <vector>

#include "app/bench_config.h"
#include "app/bench_run.h"
#include "app/ray_throughput.h"
#include "gl/context/context.h"

namespace bounce::app {

// GPU ray casting against Embree on one scene of the config (its "rays").
struct SceneRays {
    std::string scene;
    std::vector<RayThroughput> figures;
};

// Writes results.csv, results.json and report.md into `out` (atomically, each whole or not at all), and
// rays.json when the config measured ray casting. `notes` open report.md and the page (a merge's missing
// tasks, timings from several renderers).
void writeBenchReport(const std::filesystem::path& out, const BenchConfig& config, const std::vector<BenchRow>& rows,
                      const std::vector<SceneRays>& rays, const gl::ContextInfo& context,
                      const std::vector<std::string>& notes = {});

// report.html, report.js and report.css (bench/report/, static) and report-data.js (the records as
// window.BOUNCE_REPORT) into out: the page reads the images the records name (app/bench_images.h).
void writeHtmlReport(const std::filesystem::path& out, const std::vector<BenchRow>& rows,
                     const gl::ContextInfo& context, const std::vector<std::string>& notes = {});

// After writeBenchReport: the plots (speed_error.png; convergence.png and roofline.png when the rows have
// curves or bounds), and the renders that wrote NaN/Inf named on stderr. 0 when all went well, else 1.
int finishBenchReport(const std::filesystem::path& out, const std::vector<BenchRow>& rows);

// Runs the plot script on out/results.csv into out/speed_error.png; returns its exit status (0: done).
int plotSpeedError(const std::filesystem::path& out);
// bench/plot_convergence.py: convergence.png from results.json, for runs recorded with "curve": true
// (their error against the GPU time and the accumulation steps so far, beside the path tracer's).
int plotConvergence(const std::filesystem::path& out);

} // namespace bounce::app
