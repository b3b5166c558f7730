// What the shader functions that several passes share cost one invocation, counted once from their GLSL
// (gl/resource/timer.h's PassCost), so that a change to brdf.glsl, shadow.glsl or direct.frag's light
// loop is counted in one place for every pass that calls it.
#pragma once

#include "gl/resource/timer.h"

namespace bounce::gl {

class Frame;

// common/brdf.glsl's brdfEvalLobes: two transmissions, GGX's D and Smith's visibility.
constexpr double kFlopsBrdfLobes = 125;
// The same for a diffuse-only sample (the glossy lobe's weight 0: the point methods' points).
constexpr double kFlopsBrdfDiffuse = 65;
// frame/points' pointGlossyRadiance: the lobe's words unpacked and brdfGlossy towards the receiver.
constexpr double kFlopsPointGlossyRadiance = 90;

// common/shadow.glsl's shadowVisibility for one light in the form that passes off the G-buffer use: the
// shadow view (24 words) and its transform, (r+1)^2 textureGathers of four depths (r: the PCF radius, 0
// in still frames) and their weights.
PassCost shadowLookupCost(const Frame& frame);

// The loop over the lights at one shading point (common/lighting.glsl, as direct.frag, the point methods'
// ray hits and photon's gather hits run it): per punctual light about 60 flops, per emitting triangle about
// 250 (the clipped polygon's form factor), each with its record (16 words, a triangle's 12 more) and one
// shadowLookupCost. The point's own reads and writes are the caller's.
PassCost directLightsCost(const Frame& frame, double punctual, double area);

} // namespace bounce::gl
