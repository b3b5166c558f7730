#version 450 core
// GpuScan (gl/frame/gpu_sort.h), the compaction step of the photon family (photon offsets per
// path, the cut list, digit offsets of the radix sort, cluster members), as a scan over all work groups
// in the reduce-then-scan form (Harris, Sengupta and Owens, GPU Gems 3, ch. 39; Merrill and Grimshaw
// 2009): scan_reduce.comp sums every block of 4096 words, the block sums are scanned (by this pass, as
// one more level), and this pass scans each block from its offset. Every word is read twice and written
// once, as by a single work group, but by all of them. (A single pass with decoupled look-back, Merrill
// and Garland 2016, waits on other work groups, whose progress GL does not promise.)
//
// A work group takes a block: 16 consecutive words per invocation, an inclusive scan of the 256
// invocations' sums in shared memory (Hillis and Steele 1986), the words replaced by their exclusive
// prefix sums plus the block's offset, blockSums[sumsOffset + block]. At the top level there is one
// block, no offset, and its total is the scan's, into counters[totalSlot]. Integer sums: the same
// result in any order of execution.
#include "frame/scan_block.glsl"

layout(std430, binding = SSBO_SCAN) buffer ScanData { uint scanData[]; };
layout(std430, binding = SSBO_SCAN_SUMS) readonly buffer BlockSums { uint blockSums[]; };
layout(std430, binding = SSBO_SCAN_TOTALS) buffer Counters { uint counters[]; };

uniform bool topLevel;   // one block, no offset: its total is the scan's, into counters[totalSlot]
uniform uint totalSlot;

void main()
{
    uint t = gl_LocalInvocationIndex;
    uint block, first;
    if (!scanBlock(block, first)) return;
    uint v[16];
    uint sum = 0u;
    for (uint j = 0u; j < 16u; ++j) {
        v[j] = first + j < count ? scanData[dataOffset + first + j] : 0u;
        sum += v[j];
    }
    partial[t] = sum;
    barrier();
    for (uint d = 1u; d < 256u; d <<= 1) {
        uint left = t >= d ? partial[t - d] : 0u;
        barrier();
        partial[t] += left;
        barrier();
    }
    uint index = partial[t] - sum + (topLevel ? 0u : blockSums[sumsOffset + block]);
    for (uint j = 0u; j < 16u; ++j) {
        if (first + j < count) scanData[dataOffset + first + j] = index;
        index += v[j];
    }
    if (topLevel && t == 255u) counters[totalSlot] = partial[255];
}
