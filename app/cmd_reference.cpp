// bounce reference: the ground truth of a scene over chosen light paths, with the CPU path tracer of
// ref/ (cached by content, so asking twice costs nothing the second time).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/options.h"
#include "app/render_job.h"
#include "core/cornell.h"
#include "core/gltf_io.h"
#include "core/image.h"
#include "core/progress.h"
#include "ref/reference.h"

namespace bounce::app {

namespace {

const char* kUsage =
    "usage: bounce reference --scene NAME|PATH --out FILE.exr (--spp N | --noise FRACTION)\n"
    "                        [--paths P] [--size WxH] [--seed N] [--threads N] [--max-depth N]\n"
    "                        [--no-normal-maps] [--no-cache] [--cache-dir DIR] [--json FILE]\n"
    "                        [--camera POS:TARGET[:FOV]] [--light TYPE:key=value;...]...\n"
    "\n"
    "Renders the ground truth with the CPU path tracer (Embree) over the chosen light paths and writes it\n"
    "to FILE (.exr: linear radiance; .png: tone mapped; .pfm). Prints rays/s, samples per pixel, the\n"
    "relative noise reached and the time. Results are cached by scene content, camera, size, paths,\n"
    "sample count or noise target, seed and max depth.\n"
    "\n"
    "  --scene      built-in name (cornell-area, cornell-spot, cornell-point, ...), a .gltf/.glb path or a\n"
    "               scene setup (.json, assets/setups/): the same scene `render` sees\n"
    "  --out        output image (.exr, .png or .pfm)\n"
    "  --spp        samples per pixel (with --noise: the most it may take)\n"
    "  --noise      stop when the relative noise reaches this, e.g. 0.01: the mean over pixels of the\n"
    "               standard error of the pixel's mean luminance, over the image's mean luminance\n"
    "  --paths      direct, onebounce, onebounce-novis, onebounce-indirect, onebounce-novis-indirect,\n"
    "               full                                                           [full]\n"
    "  --size       image size                                                     [256x256]\n"
    "  --seed       random seed; the image depends on it and the sample count only [1]\n"
    "  --threads    worker threads, 0 = all                                        [0]\n"
    "  --max-depth  most reflections per path for --paths full, 0 = no limit        [0]\n"
    "  --no-normal-maps  shade with the vertex normals where the scene has glTF normal maps (the frame\n"
    "               parameter normalMaps=0's counterpart; cached apart from the mapped images)\n"
    "  --no-cache   render even when the cache has it, and do not store the result\n"
    "  --cache-dir  cache folder                      [$BOUNCE_CACHE or ~/.cache/bounce/references]\n"
    "  --json       also write the run's record (settings, spp, noise, seconds, rays/s) here\n";

} // namespace

int cmdReference(const Args& args)
{
    const std::string usage = std::string(kUsage) + kSceneOptionsHelp;
    const Options o(args,
                    {{"scene"},
                     {"out"},
                     {"spp"},
                     {"noise"},
                     {"paths"},
                     {"size"},
                     {"seed"},
                     {"threads"},
                     {"max-depth"},
                     {"no-normal-maps", false},
                     {"no-cache", false},
                     {"cache-dir"},
                     {"json"},
                     {"camera"},
                     {"light", true, true}},
                    usage);
    if (o.helpRequested()) {
        std::fputs(usage.c_str(), stdout);
        return 0;
    }
    if (!o.positional().empty()) throw UsageError("unexpected argument '" + o.positional()[0] + "'\n\n" + usage);

    // Everything is checked before the scene is built or anything is written.
    if (!o.has("scene")) throw UsageError(std::string("--scene is required\n\n") + usage);
    if (!o.has("out")) throw UsageError(std::string("--out is required\n\n") + usage);
    if (!o.has("spp") && !o.has("noise"))
        throw UsageError(std::string("give --spp N, --noise FRACTION or both\n\n") + usage);
    ref::RenderSettings settings;
    try {
        settings.paths = ref::parseLightPaths(o.get("paths", "full"));
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--paths: ") + e.what());
    }
    parseSize(o.get("size", "256x256"), settings.width, settings.height);
    settings.spp = o.getInt("spp", 0, 1, 1 << 24);
    settings.targetNoise = o.getDouble("noise", 0.0, 1e-6, 1.0);
    if (o.has("noise") && settings.targetNoise <= 0.0) throw UsageError("--noise must be > 0");
    const double seed = o.getDouble("seed", 1.0, 0.0, 9007199254740992.0);
    if (seed != std::floor(seed)) throw UsageError("--seed needs a non-negative integer, not '" + o.get("seed") + "'");
    settings.seed = std::uint64_t(seed);
    settings.threads = o.getInt("threads", 0, 0, 4096);
    settings.maxDepth = o.getInt("max-depth", 0, 0, 1 << 20);
    const std::filesystem::path out = o.get("out");
    const std::string ext = out.extension().string();
    if (ext != ".exr" && ext != ".png" && ext != ".pfm")
        throw UsageError("--out must end in .exr, .png or .pfm, not '" + out.string() + "'");

    const bool useCache = !o.has("no-cache");
    const std::string cacheDir = o.get("cache-dir", ref::defaultCacheDir());
    // Outputs and the cache folder are checked before the (long) render starts.
    try {
        core::checkOutputPath(out.string());
        if (o.has("json")) core::checkOutputPath(o.get("json"));
    } catch (const core::ImageError& e) {
        throw UsageError(e.what());
    }
    try {
        if (useCache) core::checkOutputPath((std::filesystem::path(cacheDir) / "write-check").string());
    } catch (const core::ImageError& e) {
        throw UsageError("the reference cache folder " + cacheDir + " is not writable: " + e.what() +
                         " (set it with --cache-dir, or skip it with --no-cache)");
    }

    core::Scene scene;
    try {
        scene = core::loadScene(o.get("scene"));
    } catch (const core::SceneError& e) {
        throw UsageError(e.what());
    }
    if (const std::string err = scene.validate(); !err.empty())
        throw UsageError(o.get("scene") + ": invalid scene:\n" + err);
    applySceneOptions(scene, o.get("camera"), o.all("light"));
    if (o.has("no-normal-maps")) core::dropNormalMaps(scene);

    std::printf("reference: %s, paths %s, %dx%d, %s\n", o.get("scene").c_str(),
                ref::lightPathsName(settings.paths).c_str(), settings.width, settings.height,
                (settings.spp > 0 && settings.targetNoise > 0.0
                     ? std::to_string(settings.spp) + " spp at most, noise target " + o.get("noise")
                 : settings.spp > 0 ? std::to_string(settings.spp) + " spp"
                                    : "noise target " + o.get("noise"))
                    .c_str());
    std::fflush(stdout);
    const ref::RenderResult r = useCache ? ref::cachedReference(scene, scene.camera, settings, cacheDir)
                                         : ref::render(scene, scene.camera, settings);

    core::FileSet files; // the image and its record appear together or not at all
    files.addImage(out.string(), r.image);

    if (r.fromCache)
        std::printf("from cache:   %s/%s.exr (rendered earlier; figures below are that run's)\n", cacheDir.c_str(),
                    ref::cacheKey(scene, scene.camera, settings).c_str());
    std::printf("samples:      %d per pixel%s\n", r.spp,
                settings.targetNoise > 0.0
                    ? (r.reachedTarget ? " (noise target reached)" : " (noise target NOT reached)")
                    : "");
    std::printf("noise:        %.4g%% relative (mean standard error / mean luminance)\n", 100.0 * r.relativeNoise);
    std::printf("time:         %.2f s\n", r.seconds);
    std::printf("rays:         %s (%s rays/s)\n", core::Progress::si(double(r.rays)).c_str(),
                core::Progress::si(r.raysPerSecond()).c_str());
    if (r.nonFiniteSamples > 0)
        std::printf("WARNING:      %llu samples were NaN/Inf and counted as black\n",
                    static_cast<unsigned long long>(r.nonFiniteSamples));
    if (o.has("json")) {
        nlohmann::json j = ref::runRecord(settings, r);
        j["scene"] = o.get("scene");
        j["fromCache"] = r.fromCache;
        j["image"] = out.string();
        files.add(o.get("json"), j.dump(2) + "\n");
    }
    try {
        files.commit();
    } catch (const core::ImageError& e) {
        throw UsageError(e.what());
    }
    std::printf("written:      %s\n", out.string().c_str());
    return 0;
}

} // namespace bounce::app
