// The photon-tree walk: depth first from the root over the heap (photon_tree.glsl) without a stack, each
// step into a node's first child (2i) or past its subtree (skipSubtree). Every walk of the tree takes its
// steps here: the k nearest photons (density.glsl) and the caustic photons near a pixel
// (photon_caustic.comp) by walkToLeafNear, the cut nodes whose kernels reach a point (cut_lookup.glsl) by
// skipSubtree.
//
// Each walk keeps its own branches, one skipSubtree per branch that leaves a subtree: llvmpipe counts the
// iterations of all loops of an invocation towards one limit (gallivm's loop limiter, 65,535), a vector of
// invocations running each loop as long as its longest lane, so two branches' loops merged into one count
// differently, and a walk that meets the limit ends at another node (some of cut_refine.comp's
// nearest-photon walks meet it on cornell-slats at 64x64: the image changed with the merged loops).
#ifndef BOUNCE_PHOTON_TREE_WALK_GLSL
#define BOUNCE_PHOTON_TREE_WALK_GLSL

#include "technique/photon/photon_tree.glsl"

// The next node after i's subtree in depth-first order over the heap (0: the walk is over).
uint skipSubtree(uint i)
{
    while ((i & 1u) == 1u) i >>= 1;
    return i == 0u ? 0u : i + 1u;
}

// The squared distance from p to the box [lo, hi] (0 inside it).
float boxDistance2(vec3 p, vec3 lo, vec3 hi)
{
    vec3 d = max(max(lo - p, p - hi), vec3(0.0));
    return dot(d, d);
}

// One step of a walk for the photons within squared distance `limit` of x: past node i's subtree when it
// holds no photons or its box lies farther, into its first child when it is an interior node; true, i
// unchanged, for a leaf within reach, whose photons (nodeRange) the caller reads before it goes on at
// skipSubtree(i).
bool walkToLeafNear(inout uint i, vec3 x, float limit)
{
    PhotonNode node = photonNodes[i];
    if (node.lo.w <= 0.0 || boxDistance2(x, node.lo.xyz, node.hi.xyz) > limit) {
        i = skipSubtree(i);
        return false;
    }
    if (!nodeIsLeaf(i)) {
        i = 2u * i;
        return false;
    }
    return true;
}

// The squared distance from x to photon ph.
float photonDistance2(Photon ph, vec3 x)
{
    vec3 d = ph.positionPath.xyz - x;
    return dot(d, d);
}

#endif
