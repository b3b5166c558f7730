#version 450 core
// One level of the cut's influence boxes, bottom-up: a cut node reaches as far as its kernel (r_p around
// its centre, Eq. 5) and its fallback kernel (twice that: photon_gather.glsl), a node above the cut as
// far as its children, a node below the cut nowhere. The gather walks the tree from the root and skips
// every subtree whose box does not hold the point: the subtree above the cut is the kd-tree of the cut's
// nodes (section 3.3).
#include "technique/photon/illumination_cut.glsl"
#include "technique/photon/tree_level.glsl"

void main()
{
    uint i = levelNode();
    if (i == 0u) return;
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38), fallbackLo = lo, fallbackHi = hi;
    if ((cutFlags(i) & kCutIn) != 0u) {
        vec4 cr = cutNodes[i].centreRadius;
        lo = cr.xyz - cr.w;
        hi = cr.xyz + cr.w;
        fallbackLo = cr.xyz - 2.0 * cr.w;
        fallbackHi = cr.xyz + 2.0 * cr.w;
    } else if (level < treeDepth) {
        uint a = 2u * i, b = 2u * i + 1u;
        lo = min(cutNodes[a].influenceLo.xyz, cutNodes[b].influenceLo.xyz);
        hi = max(cutNodes[a].influenceHi.xyz, cutNodes[b].influenceHi.xyz);
        fallbackLo = min(cutNodes[a].fallbackLo.xyz, cutNodes[b].fallbackLo.xyz);
        fallbackHi = max(cutNodes[a].fallbackHi.xyz, cutNodes[b].fallbackHi.xyz);
    }
    cutNodes[i].influenceLo.xyz = lo;
    cutNodes[i].influenceHi.xyz = hi;
    // Whole words, the unused w included: the buffer's storage starts undefined on a GPU, and a node's
    // bytes are the same in every run only if every one of them is written.
    cutNodes[i].fallbackLo = vec4(fallbackLo, 0.0);
    cutNodes[i].fallbackHi = vec4(fallbackHi, 0.0);
}
