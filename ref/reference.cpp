// Light-path names and the reference cache.
#include "ref/reference.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace bounce::ref {

namespace {

// Bump when the estimators or the BRDF (core/brdf.h) change what they compute (or fix a bias): old cache
// entries then miss. 2: the diffuse part weighted by the transmission in and out.
constexpr int kEstimatorVersion = 2;

struct Fnv1a {
    std::uint64_t h = 1469598103934665603ull;
    void bytes(const void* p, std::size_t n)
    {
        const auto* c = static_cast<const unsigned char*>(p);
        for (std::size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
    }
    template <class T>
    void pod(const T& v)
    {
        bytes(&v, sizeof v);
    }
    void text(const std::string& s)
    {
        pod(s.size());
        bytes(s.data(), s.size());
    }
};

} // namespace

nlohmann::json runRecord(const RenderSettings& settings, const RenderResult& r)
{
    nlohmann::json j;
    j["paths"] = lightPathsName(settings.paths);
    j["width"] = settings.width;
    j["height"] = settings.height;
    j["spp"] = r.spp;
    j["targetSpp"] = settings.spp;
    j["targetNoise"] = settings.targetNoise;
    if (std::isfinite(r.relativeNoise))
        j["relativeNoise"] = r.relativeNoise;
    else
        j["relativeNoise"] = nullptr; // 1 spp: no variance estimate
    j["reachedTarget"] = r.reachedTarget;
    j["seed"] = settings.seed;
    j["threads"] = settings.threads;
    j["maxDepth"] = settings.maxDepth;
    j["seconds"] = r.seconds;
    j["rays"] = r.rays;
    j["raysPerSecond"] = r.raysPerSecond();
    j["nonFiniteSamples"] = r.nonFiniteSamples;
    return j;
}

std::string defaultCacheDir()
{
    if (const char* c = std::getenv("BOUNCE_CACHE"); c && *c) return c;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/bounce/references";
    if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/bounce/references";
    return ".bounce-cache/references";
}

std::string cacheKey(const core::Scene& scene, const core::Camera& camera, const RenderSettings& settings)
{
    Fnv1a f;
    f.pod(kEstimatorVersion);
    f.pod(scene.contentHash());
    f.pod(camera.position);
    f.pod(camera.forward);
    f.pod(camera.up);
    f.pod(camera.yfovRad);
    f.pod(settings.width);
    f.pod(settings.height);
    f.text(lightPathsName(settings.paths));
    f.pod(settings.spp);
    f.pod(settings.targetNoise);
    f.pod(settings.targetNoise > 0.0 ? settings.minSpp : 0);
    f.pod(settings.seed);
    f.pod(settings.paths == LightPaths::Full ? settings.maxDepth : 0);
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(f.h));
    return lightPathsName(settings.paths) + "-" + std::to_string(settings.width) + "x" +
           std::to_string(settings.height) + "-" + hex;
}

RenderResult cachedReference(const core::Scene& scene, const core::Camera& camera, const RenderSettings& settings,
                             const std::string& cacheDir)
{
    namespace fs = std::filesystem;
    const bool cacheable = settings.timeLimitSeconds <= 0.0;
    const fs::path dir = cacheDir.empty() ? fs::path(defaultCacheDir()) : fs::path(cacheDir);
    const std::string key = cacheKey(scene, camera, settings);
    const fs::path exr = dir / (key + ".exr"), sidecar = dir / (key + ".json");

    if (cacheable && fs::exists(sidecar) && fs::exists(exr)) {
        // A sidecar that does not parse or does not match, or an EXR that does not read, is a miss:
        // the entry is rendered again and overwritten.
        try {
            std::ifstream in(sidecar);
            const nlohmann::json j = nlohmann::json::parse(in);
            if (j.at("key").get<std::string>() == key) {
                RenderResult r;
                r.image = core::readImage(exr.string());
                if (r.image.width == settings.width && r.image.height == settings.height) {
                    r.spp = j.at("spp").get<int>();
                    const nlohmann::json& noise = j.at("relativeNoise"); // null: not finite (1 spp)
                    r.relativeNoise = noise.is_number() ? noise.get<double>() : std::numeric_limits<double>::infinity();
                    r.seconds = j.at("seconds").get<double>();
                    r.rays = j.at("rays").get<std::uint64_t>();
                    r.nonFiniteSamples = j.value("nonFiniteSamples", std::uint64_t(0));
                    r.reachedTarget = j.value("reachedTarget", false);
                    r.fromCache = true;
                    return r;
                }
            }
        } catch (const std::exception&) {}
    }

    RenderResult r = render(scene, camera, settings);
    if (!cacheable) return r;
    fs::create_directories(dir);
    core::writeExr(exr.string(), r.image);
    nlohmann::json j = runRecord(settings, r);
    j["key"] = key;
    j["scene"] = scene.name;
    j["estimatorVersion"] = kEstimatorVersion;
    core::writeFileAtomic(sidecar.string(), j.dump(2) + "\n");
    return r;
}

} // namespace bounce::ref
