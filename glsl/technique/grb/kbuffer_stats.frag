#version 450 core
// Per direction: the k-buffer pixels whose depth complexity exceeded k (their receivers take no sample:
// a missing entry could pair surfaces that are not neighbours), and the largest entry count seen.
#include "technique/grb/kbuffer.glsl"

layout(std430, binding = SSBO_GRB_STATS) buffer KBufferStats {
    uint overflowPixels;
    uint largestCount;
    uint occupiedPixels;
    uint entries;
};

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    bool overflow;
    int n = kbufferCountAt(px, overflow);
#if defined(KBUFFER_ATOMIC)
    uint count = texelFetch(kbufferCount, px, 0).r; // the counter: no entry needs reading
    uint used = uint(n);
#else
    uint used = 0u;
    for (int i = 0; i < n; ++i) used += entryTexel(kbufferEntry(px, i)) != 0u ? 1u : 0u;
    uint count = used + (overflow ? 1u : 0u); // at least this many
#endif
    if (overflow) atomicAdd(overflowPixels, 1u);
    if (used > 0u) {
        atomicAdd(occupiedPixels, 1u);
        atomicAdd(entries, used);
    }
    atomicMax(largestCount, count);
}
