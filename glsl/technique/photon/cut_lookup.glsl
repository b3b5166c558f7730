// The illumination cut's irradiance at a point (section 3.3, Eqs. 4 and 5): the cut nodes whose kernels
// reach y, found through the subtree above the cut, and their cached E_p weighted by
// w_j = K(|p_j - y| / r_j) max(0, n_j . n_y), K(r) = 1 - r^2 (r <= 1). Read by the final gather
// (photon_gather.glsl) and by the test of the cut's accuracy (glsl/test/cut_irradiance.comp).
#ifndef BOUNCE_CUT_LOOKUP_GLSL
#define BOUNCE_CUT_LOOKUP_GLSL

#include "technique/photon/illumination_cut.glsl"
#include "technique/photon/tree_walk.glsl"
#ifdef CUT_GRID
#include "technique/photon/cut_grid.glsl"
#endif

struct CutLookup {
    vec3 irradiance;
    vec3 incoming;  // the weighted mean direction the irradiance comes from
    int coverage;   // 2: the kernels of Eq. 5 reach y; 1: only the fallback's (twice as wide); 0: none
};

// Node i's term of Eqs. 4 and 5 at y, added to the sums (nothing where its kernel does not reach y).
void addCutKernel(uint i, vec3 y, vec3 ny, float scale, inout vec3 e, inout float weights, inout vec3 incoming)
{
    vec4 cr = cutNodes[i].centreRadius;
    float r = length(cr.xyz - y) / (scale * cr.w);
    float w = r < 1.0 ? (1.0 - r * r) * max(0.0, dot(cutNodes[i].normalRatio.xyz, ny)) : 0.0;
    if (w > 0.0) {
        weights += w;
        e += w * cutNodes[i].irradiance.rgb;
        incoming += w * cutNodes[i].incoming.xyz;
    }
}

// Eq. 4 and 5 over the cut nodes whose kernel reaches y, found by walking the photon tree from the root
// and skipping subtrees whose influence box (cut_influence.comp) does not hold y: the subtree above the
// cut serves as the kd-tree of the cut. `scale` widens the kernels (1: Eq. 5; 2: the fallback).
vec4 cutKernelSum(vec3 y, vec3 ny, float scale, out vec3 incoming)
{
    vec3 e = vec3(0.0);
    float weights = 0.0;
    incoming = vec3(0.0);
    bool wide = scale > 1.0;
    uint i = 1u;
    while (i != 0u) {
        vec3 lo = wide ? cutNodes[i].fallbackLo.xyz : cutNodes[i].influenceLo.xyz;
        vec3 hi = wide ? cutNodes[i].fallbackHi.xyz : cutNodes[i].influenceHi.xyz;
        if (any(lessThan(y, lo)) || any(greaterThan(y, hi))) {
            i = skipSubtree(i);
        } else if ((cutFlags(i) & kCutIn) != 0u) {
            addCutKernel(i, y, ny, scale, e, weights, incoming);
            i = skipSubtree(i);
        } else if (nodeIsLeaf(i)) {
            i = skipSubtree(i);
        } else {
            i = 2u * i;
        }
    }
    return vec4(e, weights);
}

#ifdef CUT_GRID
// cutKernelSum at scale 1 from the cut grid (cut_grid.glsl): y's cell lists every node whose kernel box
// reaches y, in the walk's order, so the sum is the walk's to the bit. Not the paper's lookup: on a SIMD
// renderer a vector of rays walks as long as its longest walk, and the walk took 2/3 of the gather (570 of
// 840 ms per frame on cornell-spot at 256x256 with llvmpipe); a cell's list is a few dozen nodes
// (gl/technique/photon/README.md).
vec4 cutGridKernelSum(vec3 y, vec3 ny, out vec3 incoming)
{
    vec3 e = vec3(0.0);
    float weights = 0.0;
    incoming = vec3(0.0);
    uint c = cutGridIndex(cutGridCellOf(y));
    uint end = cutGridEntryWord(cutGrid[c + 1u]);
    for (uint a = cutGridEntryWord(cutGrid[c]); a < end; ++a)
        addCutKernel(cutGrid[a], y, ny, 1.0, e, weights, incoming);
    return vec4(e, weights);
}
#endif

// The cut's irradiance at y (normal ny): Eq. 4's normalised weights; where no kernel reaches y (a gap
// between cut nodes), the kernels at twice their radius (a fallback of ours: the paper does not say);
// where none of those reach, nothing.
CutLookup cutIrradiance(vec3 y, vec3 ny)
{
    vec3 incoming;
#ifdef CUT_GRID
    vec4 s = cutGridUsable() ? cutGridKernelSum(y, ny, incoming) : cutKernelSum(y, ny, 1.0, incoming);
#else
    vec4 s = cutKernelSum(y, ny, 1.0, incoming);
#endif
    int coverage = 2;
    if (!(s.w > 0.0)) {
        s = cutKernelSum(y, ny, 2.0, incoming);
        coverage = s.w > 0.0 ? 1 : 0;
    }
    CutLookup l = CutLookup(s.w > 0.0 ? s.rgb / s.w : vec3(0.0), ny, coverage);
    float len = length(incoming);
    if (len > 0.0) l.incoming = incoming / len;
    return l;
}

#endif
