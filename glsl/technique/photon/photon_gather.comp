#version 450 core
// Final gather at the clusters' samples (section 3.3): one work group per cluster, gatherRays cosine-
// distributed rays about the sample's normal (a Hammersley set, rotated per cluster), each hit's radiance
// (photon_gather.glsl). E = pi / N sum L_j (cosine sampling); R_j = N / sum 1 / t_j, the harmonic mean
// distance of the hits (section 3.4; misses count 1/t = 0). Each invocation sums its rays in order, then
// the group reduces its sums in a fixed order: no float atomics, the same result in every run.
#include "common/dispatch_rows.glsl"
#include "technique/photon/photon_gather.glsl"
#include "technique/photon/scatter.glsl"
#include "technique/photon/shading_clusters.glsl"

// 256 invocations, one ray each at the paper's 250-500 rays: llvmpipe ends every loop of an invocation
// once the invocation's loops together have run 65,535 iterations (gallivm's loop limiter, shared by all
// loops of a shader), and four rays' BVH and tree walks per invocation came close enough to it that
// some walks ended early (gather hits too dark).
#define GATHER_GROUP 256
layout(local_size_x = GATHER_GROUP) in;

layout(std430, binding = SSBO_PHOTON_COUNTERS) buffer Counters { uint counters[]; };

uniform uint clusterCount;
uniform uint gatherRays;
uniform float minDistance; // R_j's bounds, scene units
uniform float maxDistance;
uniform uint seed;

shared vec3 radianceSums[GATHER_GROUP];
shared float inverseDistanceSums[GATHER_GROUP];
shared uint fallbackHits[GATHER_GROUP];
shared uint uncoveredHits[GATHER_GROUP];

void main()
{
    uint k = rowGroup();
    uint t = gl_LocalInvocationID.x;
    if (k >= clusterCount) return;
    Cluster c = clusters[k];
    vec3 sum = vec3(0.0);
    float inverseSum = 0.0;
    uint fallback = 0u, uncovered = 0u;
    if (c.samplePoint.w >= 0.0) {
        vec3 x = c.samplePoint.xyz, n = c.sampleNormal.xyz;
        uint h = pcgHash(k ^ pcgHash(seed));
        vec2 shift = unitPair(h);
        for (uint j = t; j < gatherRays; j += uint(GATHER_GROUP)) {
            vec2 u = fract(vec2((float(j) + 0.5) / float(gatherRays), radicalInverse2(j)) + shift);
            vec3 dir = cosineDirection(n, u);
            Hit hit;
            if (!closestHit(x + n * rayEpsilon, dir, 0.0, 3.0e38, hit)) continue;
            int coverage;
            uint r = pcgHash(h ^ (j + 1u));
            vec2 rotation = unitPair(r);
            sum += gatherRadiance(dir, hit, rotation, coverage);
            inverseSum += 1.0 / max(hit.t, 1e-30);
            fallback += coverage == 1 ? 1u : 0u;
            uncovered += coverage == 0 ? 1u : 0u;
        }
    }
    radianceSums[t] = sum;
    inverseDistanceSums[t] = inverseSum;
    fallbackHits[t] = fallback;
    uncoveredHits[t] = uncovered;
    barrier();
    for (uint d = uint(GATHER_GROUP) / 2u; d > 0u; d >>= 1) {
        if (t < d) {
            radianceSums[t] += radianceSums[t + d];
            inverseDistanceSums[t] += inverseDistanceSums[t + d];
            fallbackHits[t] += fallbackHits[t + d];
            uncoveredHits[t] += uncoveredHits[t + d];
        }
        barrier();
    }
    if (t == 0u) {
        float r = inverseDistanceSums[0] > 0.0 ? float(gatherRays) / inverseDistanceSums[0] : maxDistance;
        clusters[k].irradiance = vec4(radianceSums[0] * (kPi / float(gatherRays)), clamp(r, minDistance, maxDistance));
        atomicAdd(counters[kCounterFirst + 1u], fallbackHits[0]);
        atomicAdd(counters[kCounterFirst + 2u], uncoveredHits[0]);
    }
}
