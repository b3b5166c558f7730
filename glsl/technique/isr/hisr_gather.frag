#version 450 core
// Hierarchical image-space radiosity, the gather (§3.5.1): like the stenciled gather of §3.2
// (technique/isr/multires_gather.frag: one quad, stencil EQUAL, light WITHOUT the receiver's rho_i), but
// each valid fragment chooses its own VPL clusters: it walks the VPL tree from every top patch with a
// stack, and refines cluster j (gathers its four children instead) when
//     |V_ij|^2 <= T |V_j|^2                                          (Eq. 8)
// with |V_ij| the distance from the fragment to the cluster's mean position, |V_j| the largest light
// distance over the patch, and T = 2 (I - tau) / (3 tau RSM_res^2) per frame (refineT; alwaysRefine
// when tau = 0: every texel, as rsm-full). Clusters that reflect nothing are skipped with their subtree.
// Departure: a cluster that spans a light-space discontinuity (range.y, vpl_tree_reduce.comp) above
// level discontinuityLevel is refined whatever its distance: its mean position floats between surfaces
// and its mean normal belongs to none of them.
#include "technique/isr/multires.glsl"
#include "technique/isr/vpl.glsl"
#include "technique/isr/vpl_tree.glsl"

layout(early_fragment_tests) in;

layout(std430, binding = 12) readonly buffer VplTree { VplNode tree[]; };
// Statistics: clusters gathered, as a 64-bit sum in two words (low, high), and fragments.
layout(std430, binding = 13) buffer TreeStats { uint gatheredLow; uint gatheredHigh; uint fragments; };

uniform int rootBegin;       // this draw's top patches [rootBegin, rootEnd) of views x topGrid^2
uniform int rootEnd;         // (long traversals take several additive draws)
uniform float refineT;       // Eq. 8's T
uniform int alwaysRefine;    // tau = 0
uniform int discontinuityLevel; // discontinuous clusters above this level are always refined

layout(location = 0) out vec4 outIllumination;

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
            int stackNode[3 * VPL_TREE_MAX_DEPTH + 2];
            int stackLevel[3 * VPL_TREE_MAX_DEPTH + 2];
            for (int root = rootBegin; root < rootEnd; ++root) {
                int sp = 0;
                stackNode[sp] = root * treeSubtreeNodes;
                stackLevel[sp] = treeDepth;
                ++sp;
                while (sp > 0) {
                    --sp;
                    int index = stackNode[sp], m = stackLevel[sp];
                    VplNode node = tree[index];
                    if (max(node.flux.r, max(node.flux.g, node.flux.b)) <= 0.0) continue;
                    if (m > 0) {
                        vec3 d = node.positionArea.xyz - p;
                        if (alwaysRefine != 0 || (node.range.y != 0.0 && m > discontinuityLevel) || dot(d, d) <= refineT * node.normal.w * node.normal.w) {
                            int base = (index / treeSubtreeNodes) * treeSubtreeNodes;
                            int code = index - base - treeLevelOffset[m];
                            int firstChild = base + treeLevelOffset[m - 1] + 4 * code;
                            for (int c = 3; c >= 0; --c) {
                                stackNode[sp] = firstChild + c;
                                stackLevel[sp] = m - 1;
                                ++sp;
                            }
                            continue;
                        }
                    }
                    Vpl v;
                    v.positionArea = node.positionArea;
                    float nl = length(node.normal.xyz);
                    v.normal = vec4(nl > 0.0 ? node.normal.xyz / nl : vec3(0.0), 0.0);
                    v.flux = node.flux;
                    sum += vplContribution(v, p, n, vec3(1.0));
                    ++gathered;
                }
            }
        }
    }
    uint old = atomicAdd(gatheredLow, gathered);
    if (old + gathered < old) atomicAdd(gatheredHigh, 1u); // carry
    if (rootBegin == 0) atomicAdd(fragments, 1u);
    outIllumination = vec4(sum, 0.0); // alpha is masked off: the stencil pass's marks stay
}
