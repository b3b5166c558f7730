#version 450 core
// One level of the point tree from the level below: boxes, counts, and the largest R_j under the node
// (the interpolation's bound: a sample reaches at most R_j times its error threshold).
#include "technique/photon/cluster_point_tree.glsl"

layout(local_size_x = 64) in;

uniform int level;

float reach(uint child)
{
    PointNode n = pointNodes[child];
    if (n.lo.w <= 0.0) return 0.0;
    if (findMSB(child) == pointTreeDepth) return clusters[floatBitsToUint(n.hi.w)].irradiance.w;
    return n.hi.w;
}

void main()
{
    uint k = gl_GlobalInvocationID.x;
    if (k >= (1u << uint(level))) return;
    uint i = (1u << uint(level)) + k;
    PointNode a = pointNodes[2u * i], b = pointNodes[2u * i + 1u];
    vec3 alo, ahi, blo, bhi;
    unpackNormalBox(a.normals, alo, ahi);
    unpackNormalBox(b.normals, blo, bhi);
    // The children's boxes were widened once already: merged as they are (packNormalBox widens again).
    pointNodes[i] = PointNode(vec4(min(a.lo.xyz, b.lo.xyz), a.lo.w + b.lo.w),
                              vec4(max(a.hi.xyz, b.hi.xyz), max(reach(2u * i), reach(2u * i + 1u))),
                              packNormalBox(min(alo, blo), max(ahi, bhi)));
}
