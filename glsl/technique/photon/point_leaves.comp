#version 450 core
// The point tree's leaves, one point each, in Morton order (cluster_point_tree.glsl: PointNode).
#include "technique/photon/cluster_point_tree.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_SORT_KEYS) readonly buffer Keys { uint keys[]; };
layout(std430, binding = SSBO_SORT_VALUES) readonly buffer Values { uint values[]; };

uniform int useSamples;

void main()
{
    uint k = gl_GlobalInvocationID.x;
    uint leaves = 1u << uint(pointTreeDepth);
    if (k >= leaves) return;
    PointNode n = PointNode(vec4(vec3(3.0e38), 0.0), vec4(vec3(-3.0e38), 0.0), packNormalBox(vec3(2.0), vec3(-2.0)));
    if (keys[k] != 0xFFFFFFFFu) {
        uint c = values[k];
        vec3 p = useSamples != 0 ? clusters[c].samplePoint.xyz : clusters[c].centre.xyz;
        vec3 normal = useSamples != 0 ? clusters[c].sampleNormal.xyz : clusters[c].normal.xyz;
        n = PointNode(vec4(p, 1.0), vec4(p, uintBitsToFloat(c)), packNormalBox(normal, normal));
    }
    pointNodes[leaves + k] = n;
}
