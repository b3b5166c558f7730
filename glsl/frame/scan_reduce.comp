#version 450 core
// The first pass of GpuScan (gl/frame/gpu_sort.h) below its top level: each work group sums
// its block of 4096 words (16 consecutive words per invocation, then a tree in shared memory) into
// blockSums[sumsOffset + block]. GpuScan scans these sums and hands them to scan_blocks.comp as the
// blocks' offsets. Integer sums: the same result in any order of execution.
#include "frame/scan_block.glsl"

layout(std430, binding = SSBO_SCAN) readonly buffer ScanData { uint scanData[]; };
layout(std430, binding = SSBO_SCAN_SUMS) writeonly buffer BlockSums { uint blockSums[]; };

void main()
{
    uint t = gl_LocalInvocationIndex;
    uint block, first;
    if (!scanBlock(block, first)) return;
    uint sum = 0u;
    for (uint j = 0u; j < 16u; ++j)
        if (first + j < count) sum += scanData[dataOffset + first + j];
    partial[t] = sum;
    barrier();
    for (uint width = 128u; width > 0u; width >>= 1) {
        if (t < width) partial[t] += partial[t + width];
        barrier();
    }
    if (t == 0u) blockSums[sumsOffset + block] = partial[0];
}
