// A batch of rays cast with glsl/common/raycast.glsl and their hits written back, for the tests and
// the `bounce rays` benchmark (gl/frame/ray_caster.h, RayBatch). Included by a compute and a fragment
// shader so that both stages are exercised.
//
// One query per pass: on llvmpipe (Mesa 22.3), a fragment shader that walked the BVH twice (closestHit,
// then anyHit) lost the first walk's result on about a sixth of the rays, while each walk alone, and
// both in a compute shader, agreed with Embree.
#ifndef BOUNCE_RAYCAST_BATCH_GLSL
#define BOUNCE_RAYCAST_BATCH_GLSL

#include "common/raycast.glsl"


struct BatchRay {
    vec4 originTMin;
    vec4 dirTMax;
};
struct BatchResult {
    uint triangle;
    float t;
    vec2 b;
    uint closest; // 1 when closestHit found a hit (queried with bit 0 of `queries`)
    uint any;     // 1 when anyHit found one (bit 1)
    uint pad0, pad1;
};

layout(std430, binding = SSBO_RAY_BATCH_RAYS) readonly buffer BatchRays { BatchRay batchRays[]; };
layout(std430, binding = SSBO_RAY_BATCH_RESULTS) writeonly buffer BatchResults { BatchResult batchResults[]; };

uniform uint rayCount;
uniform int queries; // 1: closestHit, 2: anyHit (RayBatch casts one query per pass)

// Writes only the fields of the query asked for, so that two passes fill one result.
void castBatchRay(uint i)
{
    BatchRay ray = batchRays[i];
    if (queries == 1) {
        Hit hit;
        bool found = closestHit(ray.originTMin.xyz, ray.dirTMax.xyz, ray.originTMin.w, ray.dirTMax.w, hit);
        batchResults[i].closest = found ? 1u : 0u;
        batchResults[i].triangle = found ? hit.triangle : 0xFFFFFFFFu;
        batchResults[i].t = found ? hit.t : 0.0;
        batchResults[i].b = found ? hit.b : vec2(0.0);
    } else {
        batchResults[i].any = anyHit(ray.originTMin.xyz, ray.dirTMax.xyz, ray.originTMin.w, ray.dirTMax.w) ? 1u : 0u;
    }
}

#endif
