#version 450 core
// Hierarchical image-space radiosity, the gather (§3.5.1): like the stenciled gather of §3.2
// (technique/isr/multires_gather.frag: one quad, stencil EQUAL, light WITHOUT the receiver's rho_i), but
// each valid fragment chooses its own VPL clusters: it walks the VPL tree from every top patch and
// refines cluster j (visits its four children instead) when
//     |V_ij|^2 <= T |V_j|^2                                          (Eq. 8)
// with |V_ij| the distance from the fragment to the cluster's mean position, |V_j| the largest light
// distance over the patch, and T = 2 (I - tau) / (3 tau RSM_res^2) per frame (refineT; alwaysRefine
// when tau = 0: every texel, as rsm-full). Clusters that reflect nothing are skipped with their subtree.
// Departure: a cluster that spans a light-space discontinuity (negative |V_j|, vpl_tree.glsl) above
// level discontinuityLevel is refined whatever its distance: its mean position floats between surfaces
// and its mean normal belongs to none of them.
//
// The walk needs no stack: a subtree is a complete quadtree with the children of node c at 4c .. 4c+3 of
// the next finer level, so after a node that is not refined the walk moves to its next sibling, first
// climbing while it was the last of four. The tree is read as one flat texture, as the paper stores it
// (a buffer texture over the tree's buffer: four RGBA32F texels per node, of which the walk reads three).
#include "technique/isr/hisr_walk.glsl"

layout(early_fragment_tests) in;

layout(location = 0) out vec4 outIllumination;

void main()
{
    uint gathered;
    vec3 sum = hisrGather(ivec2(gl_FragCoord.xy), 0, 1, gathered);
    hisrCount(gathered);
    outIllumination = vec4(sum, 0.0); // alpha is masked off: the stencil pass's marks stay
}
