// The tree of cluster centres (or samples) that the nearest-centre searches and the interpolation walk
// (gl/technique/photon/shading_clusters.h, bindPointTree).
#ifndef BOUNCE_CLUSTER_POINT_TREE_GLSL
#define BOUNCE_CLUSTER_POINT_TREE_GLSL

#include "technique/photon/shading_clusters.glsl"

// A tree over the clusters' centres (or samples), in Morton order, one point per leaf, in heap layout as
// the photon tree (photon_tree.glsl): level `pointTreeDepth` holds the leaves.
struct PointNode {
    vec4 lo; // xyz bounding box, w: points under the node
    vec4 hi; // xyz, w: a leaf's cluster (uint bits); above the leaves, the largest R_j under the node
    uvec4 normals; // the box of the points' normals as half floats, widened outwards (packNormalBox)
};

#ifndef POINT_TREE_CUSTOM
layout(std430, binding = SSBO_POINT_TREE) buffer PointTree { PointNode pointNodes[]; };
#endif

uniform int pointTreeDepth;

uint pointSkip(uint i)
{
    while ((i & 1u) == 1u) i >>= 1;
    return i == 0u ? 0u : i + 1u;
}

float pointBoxDistance(vec3 p, vec3 lo, vec3 hi)
{
    return length(max(max(lo - p, p - hi), vec3(0.0)));
}

// The normals' box [lo, hi] of a node as three words of half floats, each bound moved outwards by more than
// a half float's rounding near 1, so that the unpacked box still holds every normal.
uvec4 packNormalBox(vec3 lo, vec3 hi)
{
    lo -= 2e-3;
    hi += 2e-3;
    return uvec4(packHalf2x16(lo.xy), packHalf2x16(vec2(lo.z, hi.x)), packHalf2x16(hi.yz), 0u);
}
void unpackNormalBox(uvec4 w, out vec3 lo, out vec3 hi)
{
    vec2 a = unpackHalf2x16(w.x), b = unpackHalf2x16(w.y), c = unpackHalf2x16(w.z);
    lo = vec3(a, b.x);
    hi = vec3(b.y, c);
}

// A lower bound of Eq. 2's error from x, n to any point under a node: alpha times the distance to its box,
// plus the distance from n to its normals' box. The second bounds the normal term of clusterError in both
// of its forms (|n - n_k| >= that distance, and sqrt(2 - 2 n . n_k) >= |n - n_k| when |n_k| <= 1); without
// it the bound is weak where alpha is small beside the normal term (Sponza: almost nothing was pruned).
float pointNodeBound(vec3 x, vec3 n, PointNode node)
{
    vec3 nlo, nhi;
    unpackNormalBox(node.normals, nlo, nhi);
    return alpha * pointBoxDistance(x, node.lo.xyz, node.hi.xyz) + pointBoxDistance(n, nlo, nhi);
}

#endif
