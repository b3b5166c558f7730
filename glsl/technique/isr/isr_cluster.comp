#version 450 core
// Per-frame multiresolution VPL clusters (Nichols, Shopf & Wyman 2009, §3.4, Fig. 7). One invocation per
// patch of the finest sampling level (minLevel) of each RSM view. Going from maxLevel down, the first
// ancestor patch without a light-space discontinuity (common/rsm.glsl: rsmPatchContinuous) is
// the coarsest continuous patch; the test is monotone (a sub-patch of a continuous patch is continuous),
// so the finest-level patches under it agree on it and its top-left one emits it as one VPL whose solid
// angle, flux and area are the sums over its 4^level texels. A patch that is discontinuous even at
// minLevel becomes a block VPL (vpl_write.glsl). Every lit texel is thus counted exactly once.
// The paper culls the candidates in one geometry-shader pass; the modern equivalent used here is one
// compute pass that appends the survivors to the VPL cache through an atomic counter.
#include "technique/isr/vpl_write.glsl"

#include "technique/isr/bindings.glsl"
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(std430, binding = SSBO_ISR_VPL_COUNT) buffer VplCount { uint vplCount; uint vplsPerLevel[16]; };

uniform int rsmSize;
uniform int minLevel;
uniform int maxLevel;
uniform float depthThreshold;
uniform float normalThreshold;
uniform uint capacity;

void append(Vpl v, int level)
{
    uint i = atomicAdd(vplCount, 1u);
    atomicAdd(vplsPerLevel[level], 1u);
    if (i < capacity) outVpls[i] = v;
}

void main()
{
    int finest = rsmSize >> minLevel;
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    int view = int(gl_GlobalInvocationID.z);
    if (q.x >= finest || q.y >= finest) return;

    for (int l = maxLevel; l >= minLevel; --l) {
        ivec2 p = q >> (l - minLevel);
        if (!rsmPatchContinuous(p, l, view, rsmSize, depthThreshold, normalThreshold)) continue;
        if (p << (l - minLevel) != q) return; // another patch of the cluster emits it
        vec4 f = rsmFetch(rsmFlux, p, l, view, rsmSize);
        if (max(f.r, max(f.g, f.b)) <= 0.0) return; // unlit: no VPL
        vec4 n = rsmFetch(rsmNormal, p, l, view, rsmSize);
        vec3 c = rsmFetch(rsmPosition, p, l, view, rsmSize).xyz;
        append(makeVpl(view, c, n.xyz, f.rgb, f.w, n.w, float(l)), l);
        return;
    }
    // Discontinuous down to the finest sampling level: one point-sampled VPL for the patch.
    ivec2 lo = q << minLevel;
    Vpl v = blockVpl(view, lo, lo + (1 << minLevel), float(minLevel));
    if (max(v.flux.r, max(v.flux.g, v.flux.b)) > 0.0) append(v, minLevel);
}
