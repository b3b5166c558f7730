// Hierarchical image-space radiosity, the per-fragment walk of the VPL tree (§3.5.1), shared by the
// gather's two forms: hisr_gather.frag (the paper's stenciled quad) and hisr_gather.comp (one invocation
// per valid fragment of a list, where the driver's compute units outnumber its graphics units; see
// MultiresGather::gatherAsFragments). The walk and Eq. 8 are described in hisr_gather.frag.
#ifndef BOUNCE_HISR_WALK_GLSL
#define BOUNCE_HISR_WALK_GLSL

#include "technique/isr/bindings.glsl"
#include "common/multires.glsl"
#include "technique/isr/vpl.glsl"
#include "technique/isr/vpl_tree.glsl"

layout(binding = UNIT_ISR_VPL_TREE_TEXELS) uniform samplerBuffer vplTreeTexels; // node i: texels 4i .. 4i + 3 (vpl_tree.glsl)
// Statistics: clusters gathered, as a 64-bit sum in two words (low, high), and fragments.
layout(std430, binding = SSBO_ISR_TREE_STATS) buffer TreeStats { uint gatheredLow; uint gatheredHigh; uint fragments; };

uniform int rootBegin;       // this draw's top patches [rootBegin, rootEnd) of views x topGrid^2
uniform int rootEnd;         // (long traversals take several additive draws)
uniform float refineT;       // Eq. 8's T
uniform int alwaysRefine;    // tau = 0
uniform int discontinuityLevel; // discontinuous clusters above this level are always refined

// First node of level m inside a subtree: the coarser levels before it hold 1 + 4 + ... + 4^(T-m-1) nodes.
int levelOffset(int m) { return ((1 << (2 * (treeDepth - m))) - 1) / 3; }

// The light the VPL clusters send to the multiresolution fragment at `at` of the flattened buffer,
// without the receiver's diffuse colour, from the top patches rootBegin + lane, + 2 lanes, ... below
// rootEnd (one walker: lane 0 of 1); `gathered` counts the clusters.
vec3 hisrGather(ivec2 at, int lane, int lanes, out uint gathered)
{
    int level;
    ivec2 t;
    vec3 sum = vec3(0.0);
    gathered = 0u;
    if (!locateInFlattened(at, level, t)) return sum;
    MultiresPatch mp = loadPatch(level, t);
    float len = length(mp.normal);
    if (!(len > 0.0 && max(mp.diffuse.r, max(mp.diffuse.g, mp.diffuse.b)) > 0.0)) return sum;
    vec3 p = mp.position, n = mp.normal / len;
    for (int root = rootBegin + lane; root < rootEnd; root += lanes) {
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
    return sum;
}

// The statistics of one fragment's walk (the fragments counted in the first draw only).
void hisrCount(uint gathered)
{
    uint old = atomicAdd(gatheredLow, gathered);
    if (old + gathered < old) atomicAdd(gatheredHigh, 1u); // carry
    if (rootBegin == 0) atomicAdd(fragments, 1u);
}

#endif
