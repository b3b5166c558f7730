#version 450 core
// Per-frame multiresolution VPL clusters (Nichols, Shopf & Wyman 2009, §3.4, Fig. 7). One invocation per
// patch of the finest sampling level (minLevel) of each RSM view. Going from maxLevel down, the first
// ancestor patch without a light-space discontinuity (common/rsm.glsl: rsmPatchContinuous) is
// the coarsest continuous patch; the test is monotone (a sub-patch of a continuous patch is continuous),
// so the finest-level patches under it agree on it and its top-left one emits it as one VPL whose solid
// angle, flux and area are the sums over its 4^level texels. A patch that is discontinuous even at
// minLevel becomes a block VPL (vpl_write.glsl). Every lit texel is thus counted exactly once.
// The paper culls the candidates in one geometry-shader pass. Here a compaction in patch order does it, so
// that the VPL cache is the same in every run (an atomic append orders VPLs by thread timing, and the
// gather's float sums then differ in the last bits from run to run): pass 0 marks each patch that emits,
// isr_cluster_scan.comp turns the marks into output indices, pass 1 writes each VPL at its index.
#include "technique/isr/vpl_write.glsl"

#include "technique/isr/bindings.glsl"
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(std430, binding = SSBO_ISR_VPL_COUNT) buffer VplCount { uint vplCount; uint vplsPerLevel[16]; };
// Per finest-level patch (view-major, then rows): pass 0 writes 1 where the patch emits a VPL, else 0;
// pass 1 reads the scan's exclusive prefix sums, the emitting patch's index in the cache.
layout(std430, binding = SSBO_ISR_CLUSTER_SLOTS) buffer ClusterSlots { uint slots[]; };

uniform int rsmSize;
uniform int minLevel;
uniform int maxLevel;
uniform float depthThreshold;
uniform float normalThreshold;
uniform uint capacity;
uniform int writePass; // 0: mark the emitting patches; 1: write their VPLs

// The VPL finest-level patch q of `view` emits, if any, and its level.
bool clusterVpl(ivec2 q, int view, out Vpl v, out int level)
{
    for (int l = maxLevel; l >= minLevel; --l) {
        ivec2 p = q >> (l - minLevel);
        if (!rsmPatchContinuous(p, l, view, rsmSize, depthThreshold, normalThreshold)) continue;
        if (p << (l - minLevel) != q) return false; // another patch of the cluster emits it
        vec4 f = rsmFetch(rsmFlux, p, l, view, rsmSize);
        if (max(f.r, max(f.g, f.b)) <= 0.0) return false; // unlit: no VPL
        vec4 n = rsmFetch(rsmNormal, p, l, view, rsmSize);
        vec3 c = rsmFetch(rsmPosition, p, l, view, rsmSize).xyz;
        v = makeVpl(view, c, n.xyz, f.rgb, f.w, n.w, float(l));
        level = l;
        return true;
    }
    // Discontinuous down to the finest sampling level: one point-sampled VPL for the patch.
    ivec2 lo = q << minLevel;
    v = blockVpl(view, lo, lo + (1 << minLevel), float(minLevel));
    level = minLevel;
    return max(v.flux.r, max(v.flux.g, v.flux.b)) > 0.0;
}

void main()
{
    int finest = rsmSize >> minLevel;
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    int view = int(gl_GlobalInvocationID.z);
    if (q.x >= finest || q.y >= finest) return;
    uint patchIndex = uint((view * finest + q.y) * finest + q.x);

    Vpl v;
    int level;
    bool emits = clusterVpl(q, view, v, level);
    if (writePass == 0) {
        slots[patchIndex] = emits ? 1u : 0u;
    } else if (emits) {
        atomicAdd(vplsPerLevel[level], 1u); // integer counts: the same whatever the order
        if (slots[patchIndex] < capacity) outVpls[slots[patchIndex]] = v;
    }
}
