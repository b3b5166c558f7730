// The shared lit point cloud (gl/frame/points/point_cloud.h): N surface points of the frame's sampler
// (core/surface_points.h) in the order of core/point_order.h, as three std430 arrays.
//   PointSample  (triangle, barycentrics, share of the triangle's area): fixed at creation; the geometry may
//                move under it (Frame::moveVertices)
//   PointSurfel  position, area, normal, diffuse colour: recomputed every frame (point_update.comp); the
//                area is the share times the triangle's area as it is now
//   radiance     outgoing (diffuse) radiance towards any direction, RGB as half floats (point_light.comp):
//                micro-rendering §3.1 stores "the reflected radiance as half-floats in a separate array";
//                the slot holds direct light, or direct plus gathered bounces (point_relight.comp).
//   glossy       GLOSSY_POINTS (a scene with a glossy material): what a point's glossy lobe needs to send
//                its direct light towards any gatherer (pointGlossyRadiance below), since "only diffuse
//                surfaces" let the radiance be stored (micro-rendering §2.2) and point projection keeps the
//                glossy lobes at the points (Maletz et al., Fig. 12). One uvec4 per point:
//                  x  the direction towards its lights: their mean weighted by the irradiance's luminance
//                     (octahedral, common/packing.glsl); one light, as on the Cornell variants: its own
//                  y  the shadowed irradiance from them times the lobe's weight w, R and G (halves)
//                  z  B (half) and a half that is unused
//                  w  F0 RGB and sqrt(alpha) (unorm8): point_update.comp writes the surface's, and
//                     point_light.comp widens alpha by the lights' extent (point_light.glsl's widenedAlpha)
//                Indirect light reaching a glossy point is not kept: with bounces > 1 the points' glossy
//                lobes send their direct light only.
#ifndef BOUNCE_POINT_CLOUD_GLSL
#define BOUNCE_POINT_CLOUD_GLSL

#include "frame/points/bindings.glsl"
#ifdef GLOSSY_POINTS
#include "common/brdf.glsl"
#include "common/packing.glsl"
#endif

struct PointSample {
    uint triangle;
    float triangleShare; // the point's area over its triangle's, at creation
    vec2 barycentrics;   // (b1, b2) of scene.glsl's sceneTrianglePoint: p = (1 - b1 - b2) v0 + b1 v1 + b2 v2
};

struct PointSurfel {
    vec3 position;
    float areaM2;
    vec3 normal;         // unit shading normal
    uint diffuse;        // c_diff as unorm 8-bit RGB (packUnorm4x8)
};

// Each shader declares the arrays it reads (a program may use 13 storage blocks, gl/resource/
// storage_bindings.h, and a gather with the scene, the BVH and its own buffers is near that): POINT_SAMPLES,
// POINT_SURFELS, POINT_RADIANCE.
#ifdef POINT_SAMPLES
layout(std430, binding = SSBO_POINT_SAMPLES) readonly buffer PointSamples { PointSample pointSamples[]; };
#endif
#ifdef POINT_SURFELS
layout(std430, binding = SSBO_POINT_SURFELS) buffer PointSurfels { PointSurfel pointSurfels[]; };
#endif
#ifdef POINT_RADIANCE
layout(std430, binding = SSBO_POINT_RADIANCE) buffer PointRadiance { uvec2 pointRadiance[]; };
#endif
#if defined(POINT_GLOSSY) && defined(GLOSSY_POINTS)
layout(std430, binding = SSBO_POINT_GLOSSY) buffer PointGlossy { uvec4 pointGlossy[]; };
#endif

// Half floats end at 65504: radiance is clamped there (a point 1 mm from a point light would overflow to
// Inf; the points' areas are far larger than such a hot spot anyway).
const float kHalfMax = 65504.0;

uvec2 packRadiance(vec3 l)
{
    l = clamp(l, vec3(0.0), vec3(kHalfMax));
    return uvec2(packHalf2x16(l.rg), packHalf2x16(vec2(l.b, 0.0)));
}

vec3 unpackRadiance(uvec2 h) { return vec3(unpackHalf2x16(h.x), unpackHalf2x16(h.y).x); }

#ifdef GLOSSY_POINTS
// A lobe's words (above): the direction, the irradiance times w, and the material word.
uvec4 packGlossy(vec3 direction, vec3 irradiance, uint material)
{
    irradiance = clamp(irradiance, vec3(0.0), vec3(kHalfMax));
    return uvec4(packUnitVector(direction), packHalf2x16(irradiance.rg), packHalf2x16(vec2(irradiance.b, 0.0)),
                 material);
}
vec3 glossyIrradiance(uvec4 g) { return vec3(unpackHalf2x16(g.y), unpackHalf2x16(g.z).x); }

// The material word: F0 and sqrt(alpha) as unorm8 (an alpha of 0.0025, polished metal, keeps 2 digits).
uint packGlossyMaterial(vec3 f0, float alpha) { return packUnorm4x8(vec4(f0, sqrt(alpha))); }
float glossyAlpha(vec4 material) { return max(material.a * material.a, 1e-3); }

// The direct light a point's (or a hierarchy node's) glossy lobe `g` sends towards wo, its normal n:
// f_glossy(wo, wi) E with the weight already in E. Zero below either horizon.
vec3 pointGlossyRadiance(uvec4 g, vec3 n, vec3 wo)
{
    vec4 m = unpackUnorm4x8(g.w);
    BrdfParams b;
    b.diffuse = vec3(0.0);
    b.f0 = m.rgb;
    b.weight = 1.0;
    b.alpha = glossyAlpha(m);
    return brdfGlossy(b, n, wo, unpackUnitVector(g.x)) * glossyIrradiance(g);
}
#endif

#endif
