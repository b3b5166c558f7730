#version 450 core
// One quadtree level from the one below: members, summed positions and normals.
#define CLUSTERS_UNUSED
#include "technique/photon/cluster_quadtree.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform int level;

void main()
{
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    int side = quadSize >> level;
    if (q.x >= side || q.y >= side) return;
    QuadNode sum = QuadNode(vec4(0.0), vec4(0.0));
    for (int c = 0; c < 4; ++c) {
        QuadNode child = quadNodes[quadIndex(level - 1, 2 * q + ivec2(c & 1, c >> 1))];
        sum.position += child.position;
        sum.normal.xyz += child.normal.xyz;
    }
    quadNodes[quadIndex(level, q)] = sum;
}
