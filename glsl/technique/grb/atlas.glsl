// The texture atlas of global ray-bundles (Hermes et al. 2010, Sec. 4.1; core/atlas.h): where each scene
// triangle lies in it, and the static atlases every pass reads (written once per scene by atlas_fill).
#ifndef BOUNCE_GRB_ATLAS_GLSL
#define BOUNCE_GRB_ATLAS_GLSL

#include "common/packing.glsl"
#include "technique/grb/bindings.glsl"

// Three corners per scene triangle, in atlas texels (gl/technique/grb/grb_atlas.cpp uploads them).
layout(std430, binding = SSBO_GRB_ATLAS_CORNERS) readonly buffer AtlasCorners { vec2 atlasCorners[]; };

vec2 atlasCorner(uint triangle, int corner) { return atlasCorners[3u * triangle + uint(corner)]; }

#ifdef ATLAS_TEXTURES
layout(binding = UNIT_GRB_POSITION) uniform sampler2D atlasPosition;   // xyz metres, w: material + 1 (0: empty)
layout(binding = UNIT_GRB_NORMAL) uniform sampler2D atlasNormal;       // xyz shading normal, w: face normal
layout(binding = UNIT_GRB_BASE_COLOR) uniform sampler2D atlasBaseColor; // rgb base colour (textured), w: chart + 1

uniform int atlasWidth;

// Texel (x, y) of the atlas as one number, and back: what a k-buffer entry stores (plus one).
uint atlasTexelIndex(ivec2 t) { return uint(t.y) * uint(atlasWidth) + uint(t.x); }
ivec2 atlasTexelOf(uint index) { return ivec2(int(index % uint(atlasWidth)), int(index / uint(atlasWidth))); }
// The chart of texel t, plus one (exact as a float below 2^24 charts).
uint atlasChart(ivec2 t) { return uint(texelFetch(atlasBaseColor, t, 0).a); }
#endif

// The face normal, packed into one float (octahedral, 2 x 16 bits) beside the shading normal.
float packFaceNormal(vec3 n) { return uintBitsToFloat(packUnitVector(n)); }
vec3 unpackFaceNormal(float w) { return unpackUnitVector(floatBitsToUint(w)); }

#endif
