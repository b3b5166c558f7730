// What `bounce bench` runs (app/cmd_bench.cpp): the config file read and checked in full (techniques,
// parameters, scenes, reference size) before the first, long, render, so that a typo fails in a second
// with status 2 instead of after an hour.
#pragma once

#include <string>
#include <vector>

#include "app/bench_reference.h"
#include "core/camera_path.h"
#include "core/scene.h"

namespace bounce::app {

// One render of the sweep: a technique with one combination of parameter values.
struct BenchSetting {
    std::string technique;
    std::vector<std::string> sets; // key=value
    // Optional: another technique to measure against (e.g. full-resolution gathering with the same VPLs).
    std::string baseline;
    std::vector<std::string> baselineSets;
    // Optional: frames of a moving light for the temporal-coherence figure (0: none).
    int temporalFrames = 0;
    // Optional: this run's own image size (0: the config's) and scenes (empty: all of the config's).
    int width = 0, height = 0;
    std::vector<std::string> scenes;
    int warmup = -1, frames = -1; // -1: the config's
    // Progressive techniques: the error against `full` after every timed frame (accumulation step), with
    // the GPU time so far: the convergence curve (record "curve").
    bool curve = false;
    // Run only by `bounce bench --full` (run key "full": true).
    bool fullOnly = false;
    // Optional: a camera path (run key "path", e.g. bench/paths/cornell-orbit.json) rendered one frame per
    // step with no still frames, as `bounce render --path` does, instead of warm-up and still frames:
    // every frame timed, frames iK and iK+1 (K = "every") compared with path-tracer references of their
    // own camera and lights, and the flicker measured from those pairs (app/bench_run.cpp, pathRow).
    std::string pathFile;  // as the config names it; empty: a still run
    std::string pathText;  // the parsed file, dumped: what the task's id covers
    core::CameraPath path; // loaded when pathFile is set
    int every = 10;        // measured frames: iK and iK+1
    int indirectScale = 1; // the indirect light at 1/N of the resolution, as the demo's budget while moving
    int stillFrames = 0;   // > 0: at frames iK, also this many still frames at that camera, for the ratio

    bool isPath() const { return !pathFile.empty(); }

    bool runsOn(const std::string& scene) const;
};

struct BenchConfig {
    int width = 128, height = 128;
    int warmup = 2, frames = 5;
    std::vector<BenchSetting> settings; // the runs with their sweeps expanded, in the file's order
    std::vector<std::string> sceneNames;
    std::vector<core::Scene> scenes;    // loaded, one per name
    std::vector<std::string> compareTo; // references beyond the technique's own paths and `full`
    int rays = 0;                       // rays per batch of the GPU-against-Embree table per scene; 0: none
    ReferenceSpec reference;
    // The path tracer's own time against error beside the curves: `full` at these samples per pixel, at
    // the reference's size, timed and compared with the (converged) reference; one row each.
    std::vector<int> pathTracerSpp;

    int widthOf(const BenchSetting& s) const { return s.width > 0 ? s.width : width; }
    int heightOf(const BenchSetting& s) const { return s.height > 0 ? s.height : height; }
    int warmupOf(const BenchSetting& s) const { return s.warmup >= 0 ? s.warmup : warmup; }
    int framesOf(const BenchSetting& s) const { return s.frames > 0 ? s.frames : frames; }
};

// Reads the JSON config at `path` (format in `bounce bench --help`), expands the sweeps, checks every
// technique, parameter, scene and size, and loads the scenes. Throws UsageError saying what is wrong.
// `full` keeps the runs marked "full": true and adds the scenes of "fullScenes" (`bounce bench --full`);
// they are checked either way.
BenchConfig readBenchConfig(const std::string& path, const std::string& cacheDir, bool full = false);

// "k=v k=v", or "defaults" for none: how records, tables and the CSV name a setting.
std::string settingsText(const std::vector<std::string>& sets);

} // namespace bounce::app
