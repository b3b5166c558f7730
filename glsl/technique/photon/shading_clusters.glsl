// Shading clusters (section 3.2; gl/technique/photon/shading_clusters.h): the error metric of Eq. 2, the
// clusters' layout, the screen-space quadtree the seeds are placed over, and the tree of cluster
// centres (or samples) that nearest-centre searches and the interpolation walk.
#ifndef BOUNCE_SHADING_CLUSTERS_GLSL
#define BOUNCE_SHADING_CLUSTERS_GLSL

#include "technique/photon/photon.glsl"

// One shading cluster: its centre (mean position and normal of its members), its members' range in the
// pixel list sorted by cluster, its irradiance sample (the member nearest the centre by Eq. 2) and what
// the final gather measured there.
struct Cluster {
    vec4 centre;       // xyz mean member position, w: members
    vec4 normal;       // xyz unit mean member normal, w: the largest member error (temporal reuse)
    vec4 samplePoint;     // xyz the sample's position, w: its pixel index (exact in float to 2^24), or -1.0 when the cluster is empty
    vec4 sampleNormal; // xyz the sample's normal, w: unused
    vec4 irradiance;   // rgb E at the sample (final gather), w: R_j, the harmonic mean distance of its rays
    uvec4 members;     // x, y: its members' range [x, y) in the pixel list sorted by cluster (0, 0 between uses)
};

const uint kNoCluster = 0xFFFFFFFFu;    // a pixel without geometry
const uint kUnclassified = 0xFFFFFFFEu; // temporal reuse: no previous cluster takes the pixel

#ifndef CLUSTERS_CUSTOM
layout(std430, binding = SSBO_CLUSTER_CENTRES) buffer Clusters { Cluster clusters[]; };
#endif

uniform float alpha; // Eq. 2's weight of position, already divided by the scene's size (1/m)

// Eq. 2: eps = alpha |x_i - x_k| + sqrt(2 - 2 n_i . n_k). For unit normals the square root is the chord
// |n_i - n_k|, which is written so: sqrt(2 - 2 n_i . n_k) turns one ulp of the dot product of two equal
// normals into 3.5e-4, enough to hand a point between two clusters of one wall to either (an NVIDIA
// H200 decoded a normal an ulp apart in a compute and a fragment shader). A centre without a normal
// (opposite normals cancelled: meanNormal's zero fallback) keeps Eq. 2's value, sqrt(2).
float clusterError(vec3 x, vec3 n, vec3 xk, vec3 nk)
{
    float normalTerm = dot(nk, nk) > 0.5 ? length(n - nk) : sqrt(max(0.0, 2.0 - 2.0 * dot(n, nk)));
    return alpha * length(x - xk) + normalTerm;
}

// The mean of summed unit normals; when they cancel (a cluster of opposite normals), `fallback`.
vec3 meanNormal(vec3 sum, float count, vec3 fallback)
{
    float len = length(sum);
    return len > 1e-3 * max(count, 1.0) ? sum / len : fallback;
}

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

// The screen-space quadtree: level 0 is the pixels of a square of side quadSize (the viewport padded to a
// power of two), level m has (quadSize >> m)^2 nodes; levels are stored one after the other.
struct QuadNode {
    vec4 position; // xyz summed member positions, w: members
    vec4 normal;   // xyz summed member normals, w: eps_q, the summed Eq. 2 error of its members to their mean
};

layout(std430, binding = SSBO_CLUSTER_QUADTREE) buffer Quadtree { QuadNode quadNodes[]; };

uniform int quadSize;
uniform int quadLevels; // levels above the pixels: the root is level quadLevels

uint quadOffset(int level)
{
    // sum over m < level of (quadSize >> m)^2
    uint offset = 0u;
    for (int m = 0; m < level; ++m) offset += uint((quadSize >> m) * (quadSize >> m));
    return offset;
}
uint quadIndex(int level, ivec2 q) { return quadOffset(level) + uint(q.y * (quadSize >> level) + q.x); }

#endif
