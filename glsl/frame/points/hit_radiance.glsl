// What a ray's hit on the scene sends back along the ray when no point of the cloud answers for it: the
// direct light of the hit's surface, as a point there would have it (point_light.glsl), with the base
// colour's texel as the points take it (point_update.comp). Micro-rendering's ray-cast micro-pixels where no
// listed disc is near; point projection's ray-cast holes. Include after common/scene.glsl with
// SCENE_GEOMETRY, common/raycast.glsl and point_light.glsl.
#ifndef BOUNCE_HIT_RADIANCE_GLSL
#define BOUNCE_HIT_RADIANCE_GLSL

#include "common/base_color.glsl"
#include "common/material.glsl"

// Outgoing radiance towards wo of the surface point hp (normal hn) on triangle `triangle` at barycentrics b:
// every lobe where the scene has a glossy material (GLOSSY_POINTS), else the diffuse one.
vec3 hitDirectRadiance(uint triangle, vec2 b, vec3 hp, vec3 hn, vec3 wo)
{
    Material m = materials[sceneTriangleMaterial(triangle)];
    // Sponza's factors are white: without the texel the hits were 2-3x too bright.
    vec3 baseColor = materialBaseColor(m, sceneTriangleUv(triangle, b));
#ifdef GLOSSY_POINTS
    return surfaceDirectRadiance(hp, hn, wo, materialBrdf(m, baseColor));
#else
    return pointDirectRadiance(hp, hn, baseColor * (1.0 - m.baseColorMetallic.a));
#endif
}

#endif
