#version 450 core
// After the sort by cluster (the deterministic replacement of the paper's atomic sums): each cluster's
// members are one contiguous segment of the sorted pixels; its ends are where the key changes.
#include "technique/photon/shading_clusters.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_SORT_KEYS) readonly buffer Keys { uint keys[]; };

uniform uint pixelCount;
uniform uint clusterCount;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= pixelCount) return;
    uint k = keys[i];
    if (k >= clusterCount) return;
    if (i == 0u || keys[i - 1u] != k) clusters[k].members.x = i;
    if (i + 1u == pixelCount || keys[i + 1u] != k) clusters[k].members.y = i + 1u;
}
