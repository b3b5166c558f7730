// The shared lit point cloud (gl/frame/points/point_cloud.h): N surface points of the frame's sampler
// (core/surface_points.h) in the order of core/point_order.h, as three std430 arrays.
//   PointSample  (triangle, barycentrics, area): fixed at creation; the geometry may move under it
//   PointSurfel  position, area, normal, diffuse colour: recomputed every frame (point_update.comp)
//   radiance     outgoing (diffuse) radiance towards any direction, RGB as half floats (point_light.comp):
//                micro-rendering §3.1 stores "the reflected radiance as half-floats in a separate array";
//                the slot holds direct light, or direct plus gathered bounces (point_relight.comp).
#ifndef BOUNCE_POINT_CLOUD_GLSL
#define BOUNCE_POINT_CLOUD_GLSL

#include "frame/points/bindings.glsl"

struct PointSample {
    uint triangle;
    float areaM2;
    vec2 barycentrics;   // (b1, b2) of scene.glsl's sceneTrianglePoint: p = (1 - b1 - b2) v0 + b1 v1 + b2 v2
};

struct PointSurfel {
    vec3 position;
    float areaM2;
    vec3 normal;         // unit shading normal
    uint diffuse;        // c_diff as unorm 8-bit RGB (packUnorm4x8)
};

// Each shader declares the arrays it reads (a compute shader has at most 16 storage blocks, and a gather
// with the scene, the BVH and its own buffers is near that): POINT_SAMPLES, POINT_SURFELS, POINT_RADIANCE.
#ifdef POINT_SAMPLES
layout(std430, binding = SSBO_POINT_SAMPLES) readonly buffer PointSamples { PointSample pointSamples[]; };
#endif
#ifdef POINT_SURFELS
layout(std430, binding = SSBO_POINT_SURFELS) buffer PointSurfels { PointSurfel pointSurfels[]; };
#endif
#ifdef POINT_RADIANCE
layout(std430, binding = SSBO_POINT_RADIANCE) buffer PointRadiance { uvec2 pointRadiance[]; };
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

#endif
