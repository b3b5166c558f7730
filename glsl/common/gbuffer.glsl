// The G-buffer every technique reads (gl/frame/gbuffer.h), bound to texture units 0..4.
#ifndef BOUNCE_GBUFFER_GLSL
#define BOUNCE_GBUFFER_GLSL

#include "common/bindings.glsl"
layout(binding = UNIT_G_POSITION) uniform sampler2D gPosition;  // xyz world position (m), w: 1 where geometry, 0 background
layout(binding = UNIT_G_NORMAL) uniform sampler2D gNormal;    // xyz world shading normal, w: eye-space linear depth (m)
layout(binding = UNIT_G_DIFFUSE) uniform sampler2D gDiffuse;   // rgb c_diff, a: specular weight w
layout(binding = UNIT_G_SPECULAR) uniform sampler2D gSpecular;  // rgb F0, a: roughness
layout(binding = UNIT_G_EMISSION) uniform sampler2D gEmission;  // rgb emitted radiance

#endif
