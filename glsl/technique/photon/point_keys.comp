#version 450 core
// The tree of cluster centres (section 3.2: "we build a kd-tree of all cluster centers at the beginning
// of each k-means iteration"), or of cluster samples for the interpolation: Morton codes of the points;
// absent points (empty clusters, clusters without a sample) sort last.
#include "technique/photon/shading_clusters.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_SORT_KEYS) writeonly buffer Keys { uint keys[]; };
layout(std430, binding = SSBO_SORT_VALUES) writeonly buffer Values { uint values[]; };

uniform uint clusterCount;
uniform uint paddedCount; // keys up to here: absent
uniform int useSamples;
uniform vec3 boundsLo;
uniform vec3 boundsExtent;

void main()
{
    uint k = gl_GlobalInvocationID.x;
    if (k >= paddedCount) return;
    uint key = 0xFFFFFFFFu;
    if (k < clusterCount) {
        Cluster c = clusters[k];
        bool present = useSamples != 0 ? c.samplePoint.w >= 0.0 : c.centre.w > 0.0;
        if (present) key = morton30(useSamples != 0 ? c.samplePoint.xyz : c.centre.xyz, boundsLo, boundsExtent);
    }
    keys[k] = key;
    values[k] = k;
}
