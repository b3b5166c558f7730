// The VPL tree of hierarchical image-space radiosity (Nichols, Shopf & Wyman 2009, §3.5): the
// full-resolution RSM reorganised each frame into one flat array of clusters (gl/technique/isr/vpl_tree.h
// builds it). Each light view is cut into topGrid x topGrid top patches of P x P texels (P = size /
// topGrid, a power of two; the paper starts from 16^2 coarsest patches); the whole subtree of one top
// patch is stored contiguously, coarsest level first (level T = log2 P: 1 node, level T-1: 4, ...,
// level 0: P^2 texels), nodes of a level in Morton order, so the four children of node c are the
// consecutive nodes 4c .. 4c+3 of the next finer level: the clustering of Haar-wavelet coefficients.
// Subtree s (top patch (tx, ty) of view v: s = (v topGrid + ty) topGrid + tx) starts at node s x
// treeSubtreeNodes; level m of it at + treeLevelOffset[m].
#ifndef BOUNCE_ISR_VPL_TREE_GLSL
#define BOUNCE_ISR_VPL_TREE_GLSL

#define VPL_TREE_MAX_DEPTH 10

// The first three vec4 as the cache's Vpl (technique/isr/vpl.glsl), so that a node is gathered as a VPL.
struct VplNode {
    vec4 positionArea; // xyz area-weighted mean position of its lit texels (m), w: summed area A_j (m^2)
    vec4 normal;       // xyz area-weighted mean of the lit texels' unit normals (length <= 1: normalise to
                       // use), w: |V_j| max, the largest light distance of its texels with geometry (the
                       // light-space depth max-mipmap of §3.5.1), NEGATED when the cluster spans a
                       // light-space discontinuity (vpl_tree_reduce.comp): the gather decides on the
                       // first three vec4 alone
    vec4 flux;         // rgb summed reflected flux rho_j Phi_j (W), w: summed solid angle omega_j (sr)
    vec4 range;        // x: smallest light distance of its texels with geometry (1e30 when none), for the
                       // build's discontinuity test
};

uniform int treeDepth;                                // T: levels above the texels
uniform int treeTopGrid;                              // top patches per side of one view
uniform int treeSubtreeNodes;                         // nodes of one top patch's subtree
uniform int treeLevelOffset[VPL_TREE_MAX_DEPTH + 1];  // first node of level m inside a subtree

// Interleaves the bits of p (x in the even bits): children of code c are 4c + (i | j << 1).
int mortonCode(ivec2 p)
{
    int code = 0;
    for (int b = 0; b < 15; ++b) code |= ((p.x >> b) & 1) << (2 * b) | ((p.y >> b) & 1) << (2 * b + 1);
    return code;
}

#endif
