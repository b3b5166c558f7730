// The ground truth of Bounce: a CPU path tracer on Embree 3 over core::Scene, with selectable light
// paths so that every technique is measured against exactly the light transport it claims to compute.
// ref/README.md describes the estimators, the conventions and how to trust the numbers.
//
// Reproducibility: sample s of pixel (x, y) draws all its random numbers from one PCG32 stream keyed by
// (seed, x, y, s), and each pixel sums its samples in order, so an image depends on the seed and the
// sample count only: not on the thread count, the tile order or how samples were split into passes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/light_paths.h"
#include "core/scene.h"

namespace bounce::ref {

// The light-path sets live in core/ (core/light_paths.h), shared with the techniques that claim them.
using core::LightPaths;
using core::lightPathsName;
using core::lightPathsNames;
using core::parseLightPaths;

struct RenderSettings {
    LightPaths paths = LightPaths::Full;
    int width = 256;
    int height = 256;
    // Stop at spp samples per pixel, or earlier when targetNoise > 0 is reached (see relativeNoise in
    // RenderResult). With targetNoise > 0 and spp == 0 there is no sample cap.
    int spp = 0;
    double targetNoise = 0.0;
    int minSpp = 16; // the noise estimate is not trusted before this many samples
    std::uint64_t seed = 1;
    int threads = 0;             // 0: every hardware thread
    int maxDepth = 0;            // Full only: the most reflections per path; 0 = Russian roulette alone
    double timeLimitSeconds = 0; // > 0: stop after the first pass that ends past this (result says so)
    bool progress = true;        // a progress bar on stderr (core/progress.h)
};

struct RenderResult {
    core::Image image;    // mean radiance per pixel, linear RGB
    core::Image variance; // per-pixel variance of that mean (sample variance / spp), RGB
    int spp = 0;
    double relativeNoise = 0.0;         // mean over pixels of the standard error of the pixel mean (luminance),
                                        // divided by the mean luminance of the image
    double seconds = 0.0;               // wall clock of the render (scene build excluded)
    double buildSeconds = 0.0;          // Embree BVH build and light tables
    std::uint64_t rays = 0;             // rtcIntersect1 + rtcOccluded1 calls, camera rays included
    std::uint64_t nonFiniteSamples = 0; // samples that came out NaN/Inf and were counted as 0 (a bug if > 0)
    bool reachedTarget = false;         // the noise target was met (false for plain spp runs)
    bool fromCache = false;             // set by cachedReference
    double raysPerSecond() const { return seconds > 0.0 ? double(rays) / seconds : 0.0; }
};

// Throws std::invalid_argument for a bad setting (no stopping rule, sizes < 1...) or an invalid scene.
RenderResult render(const core::Scene& scene, const core::Camera& camera, const RenderSettings& settings);

// A run's record as JSON: light paths, size, spp and noise (target and reached), seed, threads, max
// depth, seconds, rays and rays/s. The cache's sidecar and `bounce reference --json` add their own keys.
nlohmann::json runRecord(const RenderSettings& settings, const RenderResult& result);

// The default cache folder: $BOUNCE_CACHE if set, else $XDG_CACHE_HOME/bounce/references, else
// $HOME/.cache/bounce/references, else ./.bounce-cache/references.
std::string defaultCacheDir();

// The path tracer's code version: what `sha256sum FILES | sha256sum` prints in the source root for the
// files sourceFiles() names (ref/ and the core/ files it computes with), taken when CMake configures,
// which it does again whenever one of them changes. Part of every cache key, so that an edited path
// tracer never reuses old entries.
std::string sourceHash();
std::vector<std::string> sourceFiles(); // relative to the source root, sorted

// The key under which a render is cached: scene.contentHash(), the camera, the size, the light paths,
// spp, the noise target (and minSpp), the seed, maxDepth and the code version (sourceHash() unless a
// test passes another). Threads are not part of it: they change nothing.
std::string cacheKey(const core::Scene& scene, const core::Camera& camera, const RenderSettings& settings,
                     const std::string& codeVersion = sourceHash());

// Looks for <cacheDir>/<key>.exr with its <key>.json sidecar; renders and stores both when absent. Each
// file goes through a temporary name unique to the writing thread and a rename, EXR first, then the JSON
// that completes the entry, so that concurrent writers of one entry (two bench runs) never mix bytes.
// The JSON holds a checksum over the EXR's bytes and its own record: an entry that is truncated,
// corrupted, or whose files are not one render's is a miss, rendered again and overwritten, never trusted.
// A cached result has no variance image; image, spp, relativeNoise, seconds and rays come from the files.
// Runs with a time limit are never cached. An empty cacheDir means defaultCacheDir().
RenderResult cachedReference(const core::Scene& scene, const core::Camera& camera, const RenderSettings& settings,
                             const std::string& cacheDir = {});

} // namespace bounce::ref
