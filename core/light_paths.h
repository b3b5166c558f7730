// Light paths, in Heckbert's notation with D|G any reflection (the BRDF of core/brdf.h): what a
// technique claims to compute (gl/technique/technique.h) and what the path tracer integrates (ref/), one
// enum for both so that every technique is measured against exactly the light transport it computes.
// See shared/scenes/cornell-box.md and ref/README.md.
#pragma once

#include <string>
#include <vector>

namespace bounce::core {

enum class LightPaths {
    Direct,                 // LE + L(D|G)E: emission seen by the camera and one reflection of the light
    OneBounce,              // Direct + L(D|G){2}E, with full visibility
    OneBounceNoVis,         // Direct + L(D|G){2}E without the visibility between x1 and x2
    OneBounceIndirect,      // L(D|G){2}E only: OneBounce - Direct
    OneBounceNoVisIndirect, // the L(D|G){2}E term of OneBounceNoVis only
    Full,                   // every path length (unbiased Russian roulette)
};

// "direct", "onebounce", "onebounce-novis", "onebounce-indirect", "onebounce-novis-indirect", "full".
// Throws std::invalid_argument naming the allowed values for anything else.
LightPaths parseLightPaths(const std::string& name);
std::string lightPathsName(LightPaths paths);
std::vector<std::string> lightPathsNames();

// Reflections of light after the first, at most (0 for Direct, 1 for the one-bounce sets, -1: unbounded).
int indirectBounces(LightPaths paths);

} // namespace bounce::core
