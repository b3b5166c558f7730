// What the shader functions that several passes share cost one invocation, counted once from their GLSL
// (gl/resource/timer.h's PassCost), so that a change to brdf.glsl, shadow.glsl or direct.frag's light
// loop is counted in one place for every pass that calls it.
#pragma once

#include "gl/resource/timer.h"

namespace bounce::gl {

class Frame;
struct FrameSettings;

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

// direct.frag's loop over the lights at one shading point: per punctual light about 60 flops and (2r+1)^2
// shadow taps (four texels each when filtered), per emitting triangle about 250 flops (the clipped
// polygon's form factor) and its taps. The pixel's own reads and writes are the caller's.
PassCost directLightsCost(const FrameSettings& settings, double punctual, double area);

} // namespace bounce::gl
