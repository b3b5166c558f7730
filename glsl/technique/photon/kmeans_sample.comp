#version 450 core
// Each cluster's irradiance sample (section 3.2: "in each cluster, we pick the shading point with the
// smallest error"): the member nearest its centre by Eq. 2 (ties: the first in pixel order), and the
// largest member error, which temporal reuse takes as the cluster's threshold next frame.
#include "common/gbuffer.glsl"
#include "technique/photon/shading_clusters.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_SORT_VALUES) readonly buffer Values { uint sortedPixels[]; };
layout(std430, binding = SSBO_PHOTON_COUNTERS) buffer Counters { uint counters[]; };

uniform uint clusterCount;
uniform ivec2 viewport;

void main()
{
    uint k = gl_GlobalInvocationID.x;
    if (k >= clusterCount) return;
    Cluster c = clusters[k];
    uvec2 range = c.members.xy;
    clusters[k].members = uvec4(0u);
    if (range.y <= range.x) {
        clusters[k].centre.w = 0.0;
        clusters[k].samplePoint = vec4(0.0, 0.0, 0.0, -1.0);
        return;
    }
    float best = 3.0e38, worst = 0.0;
    uint bestPixel = 0u;
    for (uint j = range.x; j < range.y; ++j) {
        uint p = sortedPixels[j];
        ivec2 q = ivec2(int(p % uint(viewport.x)), int(p / uint(viewport.x)));
        GSurface s = gbufferSurface(q);
        float e = clusterError(s.position, s.normal, c.centre.xyz, c.normal.xyz);
        if (e < best) {
            best = e;
            bestPixel = p;
        }
        worst = max(worst, e);
    }
    ivec2 q = ivec2(int(bestPixel % uint(viewport.x)), int(bestPixel / uint(viewport.x)));
    clusters[k].centre.w = float(range.y - range.x);
    clusters[k].normal.w = worst;
    GSurface chosen = gbufferSurface(q);
    clusters[k].samplePoint = vec4(chosen.position, float(bestPixel));
    clusters[k].sampleNormal = vec4(chosen.normal, 0.0);
    atomicAdd(counters[kCounterClusters], 1u);
}
