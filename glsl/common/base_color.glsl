// The base-colour textures of the scene (gl/frame/gpu_scene.h, one layer per texture, bound at
// UNIT_BASE_COLOR) and the alpha mask of glTF's alphaMode MASK (core::Material::cutsOut), for every
// pass that rasterises or ray-casts the scene: the G-buffer, shadow maps, RSMs, GPU ray casting.
// Needs common/scene.glsl (Material) first.
#ifndef BOUNCE_BASE_COLOR_GLSL
#define BOUNCE_BASE_COLOR_GLSL

#include "common/bindings.glsl"
layout(binding = UNIT_BASE_COLOR) uniform sampler2DArray baseColorTextures;

// The material's texel at uv: rgb linear (sRGB decoded by the texture format), a the alpha; 1 without a
// texture. Level 0 (the array has no mipmaps), so compute shaders read it alike. SCENE_NO_TEXTURES (the
// scene has none, gl/frame/frame.cpp: sceneDefines): no lookup compiled in, which a SIMD rasteriser would
// otherwise make for every pixel whatever the material.
vec4 baseColorTexel(Material m, vec2 uv)
{
#ifdef SCENE_NO_TEXTURES
    return vec4(1.0);
#else
    return m.flags.x >= 0 ? textureLod(baseColorTextures, vec3(uv, float(m.flags.x)), 0.0) : vec4(1.0);
#endif
}

// The base colour of material m at uv: its factor times its texture's texel (ray hits on the scene:
// frame/points/hit_radiance.glsl, common/scene_hit.glsl).
vec3 materialBaseColor(Material m, vec2 uv) { return m.baseColorMetallic.rgb * baseColorTexel(m, uv).rgb; }

// glTF MASK: a hole where baseColorFactor.a x texture alpha < alphaCutoff. Opaque materials carry a
// cutoff of 0 (gpu_scene.cpp), so they never cut out. Shaders use it under ALPHA_MASK only, which the
// passes define for scenes that have masked materials.
bool alphaCutOut(Material m, float textureAlpha)
{
    return intBitsToFloat(m.flags.w) * textureAlpha < intBitsToFloat(m.flags.z);
}

#endif
