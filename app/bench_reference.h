// The ground truth a benchmark compares against: cached references (ref/) of a scene's light paths at
// the benchmark's size, rendered once and reused across runs.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/scene.h"

namespace bounce::app {

struct ReferenceSpec {
    int spp = 256;
    double noise = 0.0;   // > 0: stop at this relative noise instead (spp caps it when also given)
    std::string cacheDir; // empty: ref::defaultCacheDir()
    // > 0: references at this size; images are box-downsampled to it before comparing (it must divide
    // their size). Less noise per reference pixel for the same cost, at the price of comparing only
    // what survives the downsampling (indirect light mostly does; sharp shadow edges do not).
    int width = 0, height = 0;
};

// From the config's "reference" object ({"spp": N} and/or {"noise": X}, optionally "size": "WxH");
// UsageError on bad values.
ReferenceSpec referenceSpecFrom(const nlohmann::json& reference, const std::string& cacheDir);

// The reference image of `paths` ("direct", "onebounce-novis", "full"...) for the scene's camera.
core::Image referenceImage(const core::Scene& scene, const std::string& sceneName, const std::string& paths, int width,
                           int height, const ReferenceSpec& spec);

} // namespace bounce::app
