#version 450 core
// Temporal reuse (section 3.2, "Temporal Coherence"): the previous frame's clusters that took at least one
// shading point of this frame survive, compacted in their previous order (marks scanned into positions),
// with their centres fixed; the others are eliminated.
#define CLUSTERS_CUSTOM
#include "technique/photon/shading_clusters.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_CLUSTER_SEEDS) readonly buffer Previous { Cluster previous[]; };
layout(std430, binding = SSBO_CLUSTER_CENTRES) writeonly buffer Clusters { Cluster clusters[]; };
layout(std430, binding = SSBO_SCAN) readonly buffer Positions { uint positions[]; };

uniform uint clusterCount;

void main()
{
    uint k = gl_GlobalInvocationID.x;
    if (k >= clusterCount) return;
    Cluster c = previous[k];
    if (c.members.y <= c.members.x) return;
    c.members = uvec4(0u);
    c.centre.w = 1.0;
    clusters[positions[k]] = c;
}
