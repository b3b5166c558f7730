// Progressive rendering: passes of a few samples per pixel over 16x16 tiles on a TBB arena, a running
// mean and variance per pixel (Welford), stopping at a sample count or a relative noise target.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/brdf.h"
#include "core/progress.h"
#include "core/sampling.h"
#include "ref/embree_scene.h"
#include "ref/integrator.h"
#include "ref/lights.h"
#include "ref/reference.h"

namespace bounce::ref {

namespace {

constexpr int kTile = 16;

// Welford's running mean and sum of squared deviations (Welford 1962; Knuth TAOCP 2, 4.2.2), per RGB
// channel and for luminance, which the noise figure is measured on.
struct PixelStats {
    glm::dvec3 mean{0.0};
    glm::dvec3 m2{0.0};
    double lumMean = 0.0;
    double lumM2 = 0.0;

    void add(const glm::vec3& x, double count)
    {
        const glm::dvec3 v(x);
        const glm::dvec3 delta = v - mean;
        mean += delta / count;
        m2 += delta * (v - mean);
        const double l = double(core::luminance(x));
        const double dl = l - lumMean;
        lumMean += dl / count;
        lumM2 += dl * (l - lumMean);
    }
};

// One generator per (seed, pixel, sample): the image depends on nothing else (reference.h).
core::Pcg32 sampleRng(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample)
{
    const std::uint64_t state =
        core::mixBits(core::mixBits(seed) ^ core::mixBits(pixel * 0x9e3779b97f4a7c15ull + sample));
    return core::Pcg32(state, pixel);
}

// Mean over pixels of the standard error of the pixel's mean luminance, over the mean luminance.
double relativeNoise(const std::vector<PixelStats>& stats, int spp)
{
    if (spp < 2 || stats.empty()) return std::numeric_limits<double>::infinity();
    double sumError = 0.0, sumMean = 0.0;
    const double norm = 1.0 / (double(spp) * double(spp - 1));
    for (const PixelStats& p : stats) {
        sumError += std::sqrt(std::max(0.0, p.lumM2 * norm));
        sumMean += p.lumMean;
    }
    if (sumMean <= 0.0) return sumError > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
    return sumError / sumMean;
}

void checkSettings(const RenderSettings& s)
{
    const auto bad = [](const std::string& what) { throw std::invalid_argument("render settings: " + what); };
    if (s.width < 1 || s.height < 1) bad("width and height must be at least 1");
    if (s.spp < 0) bad("spp must not be negative");
    if (!(s.targetNoise >= 0.0) || !std::isfinite(s.targetNoise)) bad("targetNoise must be a finite number >= 0");
    if (s.spp == 0 && s.targetNoise <= 0.0)
        bad("give a sample count (spp > 0), a noise target (targetNoise > 0) or both");
    if (s.threads < 0) bad("threads must not be negative (0: all hardware threads)");
    if (s.maxDepth < 0) bad("maxDepth must not be negative (0: no limit)");
    if (s.minSpp < 2) bad("minSpp must be at least 2 (a variance needs two samples)");
}

} // namespace

RenderResult render(const core::Scene& scene, const core::Camera& camera, const RenderSettings& settings)
{
    checkSettings(settings);
    using Clock = std::chrono::steady_clock;
    const auto buildStart = Clock::now();
    const bool noVisibility =
        settings.paths == LightPaths::OneBounceNoVis || settings.paths == LightPaths::OneBounceNoVisIndirect;
    const EmbreeScene geometry(scene, noVisibility);
    const LightTable lights(geometry);
    const Integrator integrator(geometry, lights, settings.paths, settings.maxDepth);
    RenderResult result;
    result.buildSeconds = std::chrono::duration<double>(Clock::now() - buildStart).count();

    const int w = settings.width, h = settings.height;
    const int tilesX = (w + kTile - 1) / kTile, tilesY = (h + kTile - 1) / kTile;
    std::vector<PixelStats> stats(std::size_t(w) * std::size_t(h));
    std::atomic<std::uint64_t> rays{0}, nonFinite{0};

    const int threads = settings.threads > 0 ? settings.threads : tbb::this_task_arena::max_concurrency();
    // TBB caps its workers at the hardware concurrency unless told otherwise; an explicit request for more
    // threads (oversubscription, or a test of thread-count independence) gets them.
    std::optional<tbb::global_control> allowMore;
    if (threads > tbb::info::default_concurrency())
        allowMore.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    tbb::task_arena arena(threads);
    const double pixels = double(w) * double(h);
    const bool noiseTarget = settings.targetNoise > 0.0;
    core::Progress::Output output;
    output.enabled = settings.progress;
    core::Progress progress("reference " + lightPathsName(settings.paths),
                            settings.spp > 0 ? settings.spp * pixels : 0.0, "samples", output);

    const auto start = Clock::now();
    int done = 0;
    double noise = std::numeric_limits<double>::infinity();
    for (;;) {
        // How many samples per pixel this pass: a growing pass (few synchronisations), never past the
        // sample cap, and with a noise target never much past the count the noise predicts
        // (noise ~ 1/sqrt(spp), so spp_needed = spp (noise / target)^2).
        int pass = std::max(1, std::min(done, 64));
        if (settings.spp > 0) pass = std::min(pass, std::max(1, settings.spp / 10));
        if (noiseTarget && done < settings.minSpp) pass = settings.minSpp - done;
        if (noiseTarget && done >= settings.minSpp) {
            const double needed = double(done) * (noise / settings.targetNoise) * (noise / settings.targetNoise);
            const double ahead = std::ceil(needed * 1.02) - double(done);
            pass = int(std::clamp(ahead, 1.0, std::max(1.0, double(done) * 0.5)));
            progress.setTotal(std::max(double(done + pass), std::ceil(needed)) * pixels);
        }
        if (settings.spp > 0) pass = std::min(pass, settings.spp - done);

        const int first = done;
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<int>(0, tilesX * tilesY), [&](const tbb::blocked_range<int>& range) {
                std::uint64_t localRays = 0, localNonFinite = 0;
                for (int tile = range.begin(); tile != range.end(); ++tile) {
                    const int x0 = (tile % tilesX) * kTile, y0 = (tile / tilesX) * kTile;
                    for (int y = y0; y < std::min(y0 + kTile, h); ++y)
                        for (int x = x0; x < std::min(x0 + kTile, w); ++x) {
                            const std::uint64_t pixel = std::uint64_t(y) * std::uint64_t(w) + std::uint64_t(x);
                            PixelStats& ps = stats[pixel];
                            for (int s = first; s < first + pass; ++s) {
                                core::Pcg32 rng = sampleRng(settings.seed, pixel, std::uint64_t(s));
                                // Box filter: a uniform position inside the pixel.
                                const glm::vec2 jitter = rng.next2();
                                const glm::vec3 dir =
                                    camera.rayDirection(float(x) + jitter.x, float(y) + jitter.y, w, h);
                                glm::vec3 l = integrator.radiance(camera.position, dir, rng, localRays);
                                if (!std::isfinite(l.x) || !std::isfinite(l.y) || !std::isfinite(l.z)) {
                                    ++localNonFinite;
                                    l = glm::vec3(0.0f);
                                }
                                ps.add(l, double(s + 1));
                            }
                        }
                    progress.add(double(pass) * double(std::min(kTile, w - x0) * std::min(kTile, h - y0)));
                }
                rays += localRays;
                nonFinite += localNonFinite;
            });
        });
        done += pass;
        noise = relativeNoise(stats, done);

        char note[64];
        if (std::isfinite(noise))
            std::snprintf(note, sizeof note, "%d spp, noise %.3g%%", done, 100.0 * noise);
        else
            std::snprintf(note, sizeof note, "%d spp", done);
        progress.setNote(note);
        if (noiseTarget && done >= settings.minSpp && noise <= settings.targetNoise) {
            result.reachedTarget = true;
            break;
        }
        if (settings.spp > 0 && done >= settings.spp) break;
        if (settings.timeLimitSeconds > 0.0 &&
            std::chrono::duration<double>(Clock::now() - start).count() >= settings.timeLimitSeconds)
            break;
    }
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    progress.finish();

    result.spp = done;
    result.relativeNoise = noise;
    result.rays = rays.load();
    result.nonFiniteSamples = nonFinite.load();
    result.image = core::Image(w, h);
    result.variance = core::Image(w, h);
    const double varianceNorm = done >= 2 ? 1.0 / (double(done) * double(done - 1)) : 0.0;
    for (std::size_t i = 0; i < stats.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            result.image.rgb[3 * i + std::size_t(c)] = float(stats[i].mean[c]);
            result.variance.rgb[3 * i + std::size_t(c)] = float(stats[i].m2[c] * varianceNorm);
        }
    }
    return result;
}

} // namespace bounce::ref
