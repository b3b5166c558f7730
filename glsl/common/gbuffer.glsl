// The G-buffer every technique reads (gl/frame/gbuffer.h), bound to texture units 0..4.
#ifndef BOUNCE_GBUFFER_GLSL
#define BOUNCE_GBUFFER_GLSL

layout(binding = 0) uniform sampler2D gPosition;  // xyz world position (m), w: 1 where geometry, 0 background
layout(binding = 1) uniform sampler2D gNormal;    // xyz world shading normal, w: eye-space linear depth (m)
layout(binding = 2) uniform sampler2D gDiffuse;   // rgb c_diff, a: specular weight w
layout(binding = 3) uniform sampler2D gSpecular;  // rgb F0, a: roughness
layout(binding = 4) uniform sampler2D gEmission;  // rgb emitted radiance

#endif
