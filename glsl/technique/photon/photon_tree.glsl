// The photon tree (gl/technique/photon/photon_tree.h): a complete binary tree over the photons in the
// tracer's order (kd order: every node a kd-tree cell; or Hilbert order), stored as a heap (node 1 the
// root, the children of i are 2i and 2i + 1, level l holds nodes [2^l, 2^(l+1))). Node k of level l holds
// the photons [floor(k N / 2^l), floor((k + 1) N / 2^l)), so the children split their parent's range
// exactly, and the leaves (level `treeDepth`) hold at most the configured number of photons. Every node
// keeps sums that its children add up to, and Eq. 3's estimate.
#ifndef BOUNCE_PHOTON_TREE_GLSL
#define BOUNCE_PHOTON_TREE_GLSL

#include "technique/photon/photon.glsl"

struct PhotonNode {
    vec4 lo;        // xyz bounding box of the photons, w: photon count
    vec4 hi;        // xyz, w: r_p, the box's largest side (at least treeMinRadius)
    vec4 power;     // rgb summed photon power (W), w: E~_p of Eq. 3 (luminance, W/m^2)
    vec4 position;  // xyz summed photon positions, w: summed luminous power
    vec4 normal;    // xyz summed normals weighted by luminous power
    vec4 incoming;  // xyz summed incoming directions weighted by luminous power
};

#ifndef PHOTON_NODES_CUSTOM
layout(std430, binding = SSBO_PHOTON_NODES) buffer PhotonNodes { PhotonNode photonNodes[]; };
#endif

uniform int treeDepth;        // level of the leaves
uniform uint treePhotons;     // N
uniform float treeMinRadius;  // r_p never goes below this (a node of one photon has a box of size 0)

int nodeLevel(uint i) { return findMSB(i); }
bool nodeIsLeaf(uint i) { return nodeLevel(i) >= treeDepth; }

// floor(k N / 2^l) without overflow.
uint nodeBoundary(uint k, int l)
{
    if (l == 0) return k == 0u ? 0u : treePhotons;
    uint msb, lsb;
    umulExtended(k, treePhotons, msb, lsb);
    return (msb << uint(32 - l)) | (lsb >> uint(l));
}
uvec2 nodeRange(uint i)
{
    int l = nodeLevel(i);
    uint k = i - (1u << uint(l));
    return uvec2(nodeBoundary(k, l), nodeBoundary(k + 1u, l));
}

vec3 nodeCentre(PhotonNode n) { return n.position.xyz / max(n.lo.w, 1.0); }
vec3 nodeNormal(PhotonNode n)
{
    float len = length(n.normal.xyz);
    return len > 0.0 ? n.normal.xyz / len : vec3(0.0, 1.0, 0.0);
}

// Eq. 3: E~_p = sum_i (w_i . n_p) Phi_i / r_p^2, with n_p the node's power-weighted mean normal, in
// luminance (the cut compares scalars).
float nodeEstimate(PhotonNode n)
{
    if (n.lo.w <= 0.0) return 0.0;
    float r = n.hi.w;
    return max(dot(nodeNormal(n), n.incoming.xyz), 0.0) / (r * r);
}

PhotonNode emptyNode()
{
    PhotonNode n;
    n.lo = vec4(vec3(3.0e38), 0.0);
    n.hi = vec4(vec3(-3.0e38), 0.0);
    n.power = vec4(0.0);
    n.position = vec4(0.0);
    n.normal = vec4(0.0);
    n.incoming = vec4(0.0);
    return n;
}

void finishNode(inout PhotonNode n)
{
    vec3 side = n.lo.w > 0.0 ? n.hi.xyz - n.lo.xyz : vec3(0.0);
    n.hi.w = max(max(side.x, max(side.y, side.z)), treeMinRadius);
    n.power.w = nodeEstimate(n);
}

#endif
