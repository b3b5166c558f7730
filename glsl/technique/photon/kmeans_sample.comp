#version 450 core
// Each cluster's irradiance sample (section 3.2: "in each cluster, we pick the shading point with the
// smallest error"): the member nearest its centre by Eq. 2 (ties: the first in pixel order), and the
// largest member error, which temporal reuse takes as the cluster's threshold next frame.
#include "technique/photon/kmeans_members.glsl"

layout(std430, binding = SSBO_PHOTON_COUNTERS) buffer Counters { uint counters[]; };

void main()
{
    uint k = gl_GlobalInvocationID.x;
    if (k >= clusterCount) return;
    uvec2 range = takeMembers(k);
    if (range.y <= range.x) {
        clusters[k].samplePoint = vec4(0.0, 0.0, 0.0, -1.0);
        return;
    }
    Cluster c = clusters[k];
    float best = 3.0e38, worst = 0.0;
    uint bestPixel = 0u;
    for (uint j = range.x; j < range.y; ++j) {
        uint p = sortedPixels[j];
        GSurface s = gbufferSurface(memberPixel(p));
        float e = clusterError(s.position, s.normal, c.centre.xyz, c.normal.xyz);
        if (e < best) {
            best = e;
            bestPixel = p;
        }
        worst = max(worst, e);
    }
    clusters[k].centre.w = float(range.y - range.x);
    clusters[k].normal.w = worst;
    GSurface chosen = gbufferSurface(memberPixel(bestPixel));
    clusters[k].samplePoint = vec4(chosen.position, float(bestPixel));
    clusters[k].sampleNormal = vec4(chosen.normal, 0.0);
    atomicAdd(counters[kCounterClusters], 1u);
}
