#version 450 core
// Temporal reuse: one mark per previous cluster that took a shading point, to be scanned.
#include "technique/photon/shading_clusters.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_SCAN) writeonly buffer Marks { uint marks[]; };

uniform uint clusterCount;

void main()
{
    uint k = gl_GlobalInvocationID.x;
    if (k >= clusterCount) return;
    marks[k] = clusters[k].members.y > clusters[k].members.x ? 1u : 0u;
}
