#include "app/bench_reference.h"

#include <cstdio>

#include "app/commands.h"
#include "app/options.h"
#include "ref/reference.h"

namespace bounce::app {

ReferenceSpec referenceSpecFrom(const nlohmann::json& r, const std::string& cacheDir)
{
    ReferenceSpec s;
    s.cacheDir = cacheDir;
    if (!r.is_object()) throw UsageError("bench config: \"reference\" must be an object like {\"spp\": 256}");
    s.spp = r.value("spp", r.contains("noise") ? 0 : 256);
    s.noise = r.value("noise", 0.0);
    if (s.spp < 0 || s.noise < 0.0 || (s.spp == 0 && s.noise <= 0.0))
        throw UsageError("bench config: \"reference\" needs spp > 0 or noise > 0");
    if (r.contains("size")) parseSize(r["size"].get<std::string>(), s.width, s.height);
    return s;
}

core::Image referenceImage(const core::Scene& scene, const std::string& sceneName, const std::string& paths, int width,
                           int height, const ReferenceSpec& spec)
{
    ref::RenderSettings rs;
    try {
        rs.paths = ref::parseLightPaths(paths);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    rs.width = width;
    rs.height = height;
    rs.spp = spec.spp;
    rs.targetNoise = spec.noise;
    const ref::RenderResult r = ref::cachedReference(scene, scene.camera, rs, spec.cacheDir);
    std::printf("reference %s / %s: %d spp, noise %.3f%%%s\n", sceneName.c_str(), paths.c_str(), r.spp,
                100.0 * r.relativeNoise, r.fromCache ? " (cached)" : "");
    return r.image;
}

} // namespace bounce::app
