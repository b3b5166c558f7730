#version 450 core
// The k-buffer as kbuffer.glsl reads it, written out for the CPU (tests, the stencil-routing probe):
// entry i of every pixel into layer i, and the pixel's count (the fragment count for KBUFFER_ATOMIC, else
// the entries plus one where the pixel overflowed) with the overflow flag in the top bit.
#include "technique/grb/kbuffer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rg32f, binding = 0) uniform writeonly image2DArray outEntries;
layout(r32ui, binding = 1) uniform writeonly uimage2D outCount;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, ivec2(kbufferSize)))) return;
    bool overflow;
    int n = kbufferCountAt(px, overflow);
    uint used = 0u;
    for (int i = 0; i < KBUFFER_K; ++i) {
        vec2 e = i < n ? kbufferEntry(px, i) : vec2(0.0);
        if (entryTexel(e) != 0u) ++used;
        imageStore(outEntries, ivec3(px, i), vec4(e, 0.0, 0.0));
    }
#if defined(KBUFFER_ATOMIC)
    uint count = texelFetch(kbufferCount, px, 0).r;
#else
    uint count = used + (overflow ? 1u : 0u);
#endif
    imageStore(outCount, px, uvec4(count | (overflow ? 0x80000000u : 0u)));
}
