// A material of the scene (common/scene.glsl) as the one BRDF (common/brdf.glsl).
#ifndef BOUNCE_MATERIAL_GLSL
#define BOUNCE_MATERIAL_GLSL

#include "common/brdf.glsl"
#include "common/scene.glsl"

// The BRDF of material m at a point whose base colour is baseColor: the material's factor times its
// texture's texel there (base_color.glsl's materialBaseColor), or a copy of that product (global
// ray-bundles' base-colour atlas). Every pass that shades the scene from its materials: the G-buffer
// (frame/gbuffer.frag), the point cloud (frame/points/point_update.comp, hit_radiance.glsl), the photons'
// and gather rays' hits (scene_hit.glsl), the ray-bundles' atlas texels (grb/radiance.glsl,
// grb/direct_seed.frag).
BrdfParams materialBrdf(Material m, vec3 baseColor)
{
    return brdfParams(baseColor, m.baseColorMetallic.a, m.emissionRoughness.a, m.specularColorSpecular.a,
                      m.specularColorSpecular.rgb);
}

#endif
