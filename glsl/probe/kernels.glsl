// The machine probe's kernels (gl/probe/machine_probe.h), shared by its fragment and compute versions so
// that both stages run exactly the same work.
#ifndef BOUNCE_PROBE_KERNELS_GLSL
#define BOUNCE_PROBE_KERNELS_GLSL

// Arithmetic: two independent chains of vec4 FMAs, `iterations` long. 8 flops per chain step, 16 per
// iteration (kFlopsPerIteration in machine_probe.cpp). Two chains keep a 2x2 or 4x4 SIMD block of
// invocations in registers while giving the FMA units independent work.
vec4 fmaChains(vec4 seed, int iterations, vec4 a, vec4 b)
{
    vec4 x = seed, y = seed + 1.0;
    for (int i = 0; i < iterations; ++i) {
        x = fma(x, a, b);
        y = fma(y, a, b);
    }
    return x + y;
}

// Texel fetch rate: `count` fetches from a small texture that stays in cache, at addresses that differ
// per invocation and per fetch (no two consecutive fetches of one invocation hit the same texel).
vec4 fetchLoop(sampler2D small, ivec2 p, int count)
{
    ivec2 size = textureSize(small, 0);
    vec4 sum = vec4(0.0);
    for (int i = 0; i < count; ++i) sum += texelFetch(small, (p + ivec2(7 * i, 3 * i)) % size, 0);
    return sum;
}

#endif
