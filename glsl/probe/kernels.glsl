// The machine probe's kernels (gl/probe/machine_probe.h), shared by its fragment and compute versions so
// that both stages run exactly the same work.
//
// Each kernel is written as straight-line code where it can be: a shader loop costs a software
// rasteriser far more than its body on a GPU (llvmpipe keeps a masked loop's live values in memory and
// tests its mask every iteration), so a kernel in a loop measures the loop, not the unit it is named
// after. The first probe ran its FMA chains in a 128-iteration loop and read 14 GFLOP/s on a machine
// whose straight-line FMA kernel reaches 148 (measured here, Mesa 22.3 llvmpipe, 2 cores).
#ifndef BOUNCE_PROBE_KERNELS_GLSL
#define BOUNCE_PROBE_KERNELS_GLSL

#include "probe/bindings.glsl"

// Arithmetic: eight independent chains of vec4 FMAs, FMA_STEPS long, unrolled: 8 chains x 4 components x
// 2 flops = 64 flops per step (kFlopsPerFmaStep in machine_probe.cpp). Eight chains cover the FMA latency of
// a CPU's two FMA pipes and of a GPU's; the chains stay in registers.
#define FMA_STEPS 16
vec4 fmaChains(vec4 seed, vec4 a, vec4 b)
{
    vec4 c0 = seed, c1 = seed + 1.0, c2 = seed + 2.0, c3 = seed + 3.0;
    vec4 c4 = seed + 4.0, c5 = seed + 5.0, c6 = seed + 6.0, c7 = seed + 7.0;
#define FMA_STEP                                                                                                   \
    c0 = fma(c0, a, b);                                                                                            \
    c1 = fma(c1, a, b);                                                                                            \
    c2 = fma(c2, a, b);                                                                                            \
    c3 = fma(c3, a, b);                                                                                            \
    c4 = fma(c4, a, b);                                                                                            \
    c5 = fma(c5, a, b);                                                                                            \
    c6 = fma(c6, a, b);                                                                                            \
    c7 = fma(c7, a, b);
#define FMA_STEP4 FMA_STEP FMA_STEP FMA_STEP FMA_STEP
    FMA_STEP4 FMA_STEP4 FMA_STEP4 FMA_STEP4 // FMA_STEPS = 16
    return ((c0 + c1) + (c2 + c3)) + ((c4 + c5) + (c6 + c7));
}

// Texel fetch rate: FETCHES (32) fetches from a small power-of-two texture that stays in cache, at
// addresses that differ per invocation and per fetch, unrolled. The address wraps with a mask: an integer
// modulo is a scalar division per lane on a CPU and halved the rate the first probe read.
#define FETCHES 32
vec4 fetchUnrolled(sampler2D small, ivec2 p)
{
    ivec2 mask = textureSize(small, 0) - 1;
    vec4 sum = vec4(0.0);
#define FETCH(i) sum += texelFetch(small, (p + ivec2(7 * (i), 3 * (i))) & mask, 0);
#define FETCH4(i) FETCH(i) FETCH(i + 1) FETCH(i + 2) FETCH(i + 3)
    FETCH4(0) FETCH4(4) FETCH4(8) FETCH4(12) FETCH4(16) FETCH4(20) FETCH4(24) FETCH4(28)
    return sum;
}

// Uniform-block reads the way a gather makes them: a loop over `count` records of three vec4 (a VPL,
// glsl/technique/isr/vpl.glsl), every invocation reading the same record at the same time, with as little
// arithmetic as keeps the reads alive (UNIFORM_WORDS_PER_RECORD = 12 words per iteration). A GPU
// broadcasts such reads from its constant cache; a software rasteriser may load them lane by lane.
#define UNIFORM_RECORDS 256
#define UNIFORM_WORDS_PER_RECORD 12
struct ProbeRecord {
    vec4 a, b, c;
};
layout(std140, binding = UBO_PROBE_RECORDS) uniform ProbeRecords { ProbeRecord probeRecords[UNIFORM_RECORDS]; };
vec4 uniformLoop(int count, vec4 seed)
{
    vec4 sum = seed;
    for (int i = 0; i < count; ++i) sum += probeRecords[i].a * probeRecords[i].b + probeRecords[i].c;
    return sum;
}

#endif
