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
#include "technique/isr/bindings.glsl"
#include "common/multires.glsl"
#include "technique/isr/vpl.glsl"
#include "technique/isr/vpl_tree.glsl"

layout(early_fragment_tests) in;

layout(binding = UNIT_ISR_VPL_TREE_TEXELS) uniform samplerBuffer vplTreeTexels; // node i: texels 4i .. 4i + 3 (vpl_tree.glsl)
// Statistics: clusters gathered, as a 64-bit sum in two words (low, high), and fragments.
layout(std430, binding = SSBO_ISR_TREE_STATS) buffer TreeStats { uint gatheredLow; uint gatheredHigh; uint fragments; };

uniform int rootBegin;       // this draw's top patches [rootBegin, rootEnd) of views x topGrid^2
uniform int rootEnd;         // (long traversals take several additive draws)
uniform float refineT;       // Eq. 8's T
uniform int alwaysRefine;    // tau = 0
uniform int discontinuityLevel; // discontinuous clusters above this level are always refined

layout(location = 0) out vec4 outIllumination;

// First node of level m inside a subtree: the coarser levels before it hold 1 + 4 + ... + 4^(T-m-1) nodes.
int levelOffset(int m) { return ((1 << (2 * (treeDepth - m))) - 1) / 3; }

void main()
{
    int level;
    ivec2 t;
    vec3 sum = vec3(0.0);
    uint gathered = 0u;
    if (locateInFlattened(ivec2(gl_FragCoord.xy), level, t)) {
        MultiresPatch mp = loadPatch(level, t);
        float len = length(mp.normal);
        if (len > 0.0 && max(mp.diffuse.r, max(mp.diffuse.g, mp.diffuse.b)) > 0.0) {
            vec3 p = mp.position, n = mp.normal / len;
            for (int root = rootBegin; root < rootEnd; ++root) {
                int base = root * treeSubtreeNodes;
                int m = treeDepth, code = 0; // the top patch: the one node of the coarsest level
                for (;;) {
                    int texel = 4 * (base + levelOffset(m) + code);
                    vec4 positionArea = texelFetch(vplTreeTexels, texel);
                    vec4 normalDistance = texelFetch(vplTreeTexels, texel + 1);
                    vec4 flux = texelFetch(vplTreeTexels, texel + 2);
                    if (max(flux.r, max(flux.g, flux.b)) > 0.0) {
                        vec3 d = positionArea.xyz - p;
                        bool refine = m > 0 &&
                                      (alwaysRefine != 0 || dot(d, d) <= refineT * normalDistance.w * normalDistance.w ||
                                       (m > discontinuityLevel && normalDistance.w < 0.0));
                        if (refine) {
                            --m;
                            code *= 4;
                            continue;
                        }
                        float nl = length(normalDistance.xyz);
                        Vpl v;
                        v.positionArea = positionArea;
                        v.normal = vec4(nl > 0.0 ? normalDistance.xyz / nl : vec3(0.0), 0.0);
                        v.flux = flux;
                        sum += vplContribution(v, p, n, vec3(1.0));
                        ++gathered;
                    }
                    while (m < treeDepth && (code & 3) == 3) { // the last of four: up to the parent
                        code >>= 2;
                        ++m;
                    }
                    if (m == treeDepth) break; // back at the top patch: its subtree is done
                    ++code;
                }
            }
        }
    }
    uint old = atomicAdd(gatheredLow, gathered);
    if (old + gathered < old) atomicAdd(gatheredHigh, 1u); // carry
    if (rootBegin == 0) atomicAdd(fragments, 1u);
    outIllumination = vec4(sum, 0.0); // alpha is masked off: the stencil pass's marks stay
}
