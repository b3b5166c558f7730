#version 450 core
// One pass of the stable LSD radix sort (gl/frame/gpu_sort.h): invocation r counts the 4-bit
// digits (bits [shift, shift + 4)) of the keys of its run [r L, r L + L) into counts[digit * runs + r].
// The digit-major exclusive scan of these counts gives each run the first output slot of each digit.
#include "frame/radix_pass.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = SSBO_SORT_COUNTS) writeonly buffer Counts { uint counts[]; };

void main()
{
    uint r = gl_GlobalInvocationID.x;
    if (r >= runs) return;
    uint c[16];
    for (int d = 0; d < 16; ++d) c[d] = 0u;
    uint begin = r * runLength, end = min(begin + runLength, count);
    for (uint i = begin; i < end; ++i) c[radixDigit(keys[i])] += 1u;
    for (uint d = 0u; d < 16u; ++d) counts[d * runs + r] = c[d];
}
