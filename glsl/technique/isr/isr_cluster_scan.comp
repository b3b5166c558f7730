#version 450 core
// The compaction step between isr_cluster.comp's two passes: the exclusive prefix sum of the per-patch
// marks (1: the patch emits a VPL) gives each emitting patch its index in the VPL cache, in patch order,
// and the total is the VPL count. One work group of 1024 invocations (the least GL guarantees), each
// summing a contiguous run of marks, then a scan of the 1024 run sums in shared memory (Hillis and Steele
// 1986). Integer sums: exact in any order. The defaults give 4096 marks per RSM view, 4 per invocation; one
// group still serves the largest setting (2048^2 texels, minLevel 0, six views: 25,000 marks each).
#include "technique/isr/bindings.glsl"
layout(local_size_x = 1024) in;

layout(std430, binding = SSBO_ISR_VPL_COUNT) buffer VplCount { uint vplCount; uint vplsPerLevel[16]; };
layout(std430, binding = SSBO_ISR_CLUSTER_SLOTS) buffer ClusterSlots { uint slots[]; };

uniform uint patches; // marks in slots

shared uint runSums[1024];

void main()
{
    uint t = gl_LocalInvocationID.x;
    uint run = (patches + 1023u) / 1024u;
    uint begin = min(t * run, patches);
    uint end = min(begin + run, patches);
    uint sum = 0u;
    for (uint i = begin; i < end; ++i) sum += slots[i];
    runSums[t] = sum;
    barrier();
    for (uint d = 1u; d < 1024u; d <<= 1) {
        uint left = t >= d ? runSums[t - d] : 0u;
        barrier();
        runSums[t] += left;
        barrier();
    }
    uint index = runSums[t] - sum; // inclusive to exclusive
    for (uint i = begin; i < end; ++i) {
        uint mark = slots[i];
        slots[i] = index;
        index += mark;
    }
    if (t == 1023u) vplCount = runSums[1023];
}
