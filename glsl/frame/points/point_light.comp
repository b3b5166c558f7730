#version 450 core
// "point-light": direct light at every point by the frame's estimator (a shadow ray per light where the lights are
// punctual and the frame casts rays, point_light.glsl; the shadow maps otherwise), stored as half floats
// (micro-rendering §4, "One-Bounce Indirect Illumination": "directly lighting the point hierarchy, e.g.
// using shadow mapping techniques"; point projection §4, "Primary Lights"). With bounces > 1 the direct
// part is kept apart too, for point_relight.comp to add gathered light to. GLOSSY_POINTS: what the glossy
// lobes need as well (point_cloud.glsl's `glossy`).
#define POINT_SURFELS
#define POINT_RADIANCE
#define POINT_GLOSSY
#include "frame/points/point_cloud.glsl"
#include "frame/points/point_light.glsl"

layout(local_size_x = 64) in;
#ifdef KEEP_DIRECT
layout(std430, binding = SSBO_POINT_DIRECT) writeonly buffer PointDirect { uvec2 pointDirect[]; };
#endif
uniform uint pointCount;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= pointCount) return;
    PointSurfel s = pointSurfels[i];
    vec4 diffuseWeight = unpackUnorm4x8(s.diffuse);
#ifdef GLOSSY_POINTS
    // Every point: a metal's diffuse colour is black, and its glossy lobe is all it sends.
    vec4 material = unpackUnorm4x8(pointGlossy[i].w); // F0, sqrt(alpha) of the surface (point_update.comp)
    BrdfParams brdf = BrdfParams(diffuseWeight.rgb, material.rgb, diffuseWeight.a, 1.0); // alpha is not read
    PointLight pl = pointDirectLight(s.position, s.normal, brdf);
    float alpha = widenedAlpha(material.a * material.a, pl.spread2);
    pointGlossy[i] = packGlossy(pl.direction, pl.irradiance * diffuseWeight.a, packGlossyMaterial(material.rgb, alpha));
    uvec2 h = packRadiance(pl.radiance);
#else
    uvec2 h = packRadiance(pointDirectRadiance(s.position, s.normal, diffuseWeight.rgb));
#endif
    pointRadiance[i] = h;
#ifdef KEEP_DIRECT
    pointDirect[i] = h;
#endif
}
