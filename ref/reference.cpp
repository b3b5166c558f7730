// Light-path names and the reference cache.
#include "ref/reference.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/hash.h"

namespace bounce::ref {

namespace {

using core::Fnv1a;

// The keys and checksums of the entries on disk were made with the legacy basis (core/hash.h).
Fnv1a cacheHash()
{
    return Fnv1a(Fnv1a::kLegacyBasis);
}

// A string's length, then its bytes.
void addText(Fnv1a& f, std::string_view s)
{
    f.addBytesOf(s.size());
    f.add(s);
}

// What an entry's sidecar vouches for: the EXR's bytes and the sidecar's own record (everything but the
// checksum, in nlohmann's canonical dump: sorted keys, numbers that read back exactly).
std::string entryChecksum(const std::string& exrBytes, const nlohmann::json& record)
{
    Fnv1a f = cacheHash();
    addText(f, exrBytes);
    addText(f, record.dump());
    return f.hex();
}

std::string readWholeFile(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (!in) throw std::runtime_error("cannot read " + path.string());
    return bytes.str();
}

// The cached result when <key>.exr and <key>.json form a complete, intact entry for this key and size;
// nothing when they are absent; throws when they are present but do not check out.
std::optional<RenderResult> readEntry(const std::filesystem::path& exr, const std::filesystem::path& sidecar,
                                      const std::string& key, const RenderSettings& settings)
{
    if (!std::filesystem::exists(sidecar) || !std::filesystem::exists(exr)) return std::nullopt;
    // Read while another writer replaces the entry, the two files may come from different renders: the
    // checksum refuses such a pair unless the EXR bytes are the same (a deterministic render).
    const std::string exrBytes = readWholeFile(exr);
    nlohmann::json record = nlohmann::json::parse(readWholeFile(sidecar));
    const std::string checksum = record.at("checksum").get<std::string>();
    record.erase("checksum");
    if (checksum != entryChecksum(exrBytes, record)) throw std::runtime_error("checksum mismatch");
    if (record.at("key").get<std::string>() != key) throw std::runtime_error("sidecar of another key");
    RenderResult r;
    r.image = core::decodeImage(exr.string(), exrBytes);
    if (r.image.width != settings.width || r.image.height != settings.height)
        throw std::runtime_error("image of another size");
    r.spp = record.at("spp").get<int>();
    const nlohmann::json& noise = record.at("relativeNoise"); // null: not finite (1 spp)
    r.relativeNoise = noise.is_number() ? noise.get<double>() : std::numeric_limits<double>::infinity();
    r.seconds = record.at("seconds").get<double>();
    r.rays = record.at("rays").get<std::uint64_t>();
    r.nonFiniteSamples = record.value("nonFiniteSamples", std::uint64_t(0));
    r.reachedTarget = record.value("reachedTarget", false);
    r.fromCache = true;
    return r;
}

} // namespace

std::string sourceHash()
{
    return BOUNCE_REF_SOURCE_HASH;
}

std::vector<std::string> sourceFiles()
{
    std::vector<std::string> files;
    std::istringstream list(BOUNCE_REF_SOURCE_FILES);
    for (std::string f; list >> f;) files.push_back(f);
    return files;
}

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

std::string cacheKey(const core::Scene& scene, const core::Camera& camera, const RenderSettings& settings,
                     const std::string& codeVersion)
{
    Fnv1a f = cacheHash();
    addText(f, codeVersion);
    f.addBytesOf(scene.contentHash());
    f.addBytesOf(camera.position);
    f.addBytesOf(camera.forward);
    f.addBytesOf(camera.up);
    f.addBytesOf(camera.yfovRad);
    f.addBytesOf(settings.width);
    f.addBytesOf(settings.height);
    addText(f, lightPathsName(settings.paths));
    f.addBytesOf(settings.spp);
    f.addBytesOf(settings.targetNoise);
    f.addBytesOf(settings.targetNoise > 0.0 ? settings.minSpp : 0);
    f.addBytesOf(settings.seed);
    f.addBytesOf(settings.paths == LightPaths::Full ? settings.maxDepth : 0);
    return lightPathsName(settings.paths) + "-" + std::to_string(settings.width) + "x" +
           std::to_string(settings.height) + "-" + f.hex();
}

RenderResult cachedReference(const core::Scene& scene, const core::Camera& camera, const RenderSettings& settings,
                             const std::string& cacheDir)
{
    namespace fs = std::filesystem;
    const bool cacheable = settings.timeLimitSeconds <= 0.0;
    const fs::path dir = cacheDir.empty() ? fs::path(defaultCacheDir()) : fs::path(cacheDir);
    const std::string key = cacheKey(scene, camera, settings);
    const fs::path exr = dir / (key + ".exr"), sidecar = dir / (key + ".json");

    if (cacheable) {
        try {
            if (std::optional<RenderResult> cached = readEntry(exr, sidecar, key, settings)) return *cached;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "reference cache: entry %s is damaged (%s); rendering it again\n",
                         exr.string().c_str(), e.what());
        }
    }

    RenderResult r = render(scene, camera, settings);
    if (!cacheable) return r;
    fs::create_directories(dir);
    const std::string exrBytes = core::encodeImage(exr.string(), r.image);
    nlohmann::json j = runRecord(settings, r);
    j["key"] = key;
    j["scene"] = scene.name;
    j["sourceHash"] = sourceHash();
    j["checksum"] = entryChecksum(exrBytes, j);
    core::writeFileAtomic(exr.string(), exrBytes);
    core::writeFileAtomic(sidecar.string(), j.dump(2) + "\n");
    return r;
}

} // namespace bounce::ref
