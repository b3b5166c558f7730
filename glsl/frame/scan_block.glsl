// What the two passes of one level of GpuScan share (scan_reduce.comp, scan_blocks.comp; gl/frame/
// gpu_sort.h): the array, the block of 4096 words each work group takes (16 consecutive words per
// invocation of 256), and the invocations' sums in shared memory.
#ifndef BOUNCE_SCAN_BLOCK_GLSL
#define BOUNCE_SCAN_BLOCK_GLSL

#include "frame/sort_bindings.glsl"
#include "common/dispatch_rows.glsl"
layout(local_size_x = 256) in;

uniform uint dataOffset; // the array is scanData[dataOffset .. dataOffset + count)
uniform uint count;
uniform uint blocks;     // ceil(count / 4096), at least 1; a dispatch in rows runs groups past it
uniform uint sumsOffset;

shared uint partial[256];

// This work group's block and the first of this invocation's 16 words in it; false for a group past the
// last block, which has nothing to do.
bool scanBlock(out uint block, out uint first)
{
    block = rowGroup();
    if (block >= blocks) return false;
    first = block * 4096u + gl_LocalInvocationIndex * 16u;
    return true;
}

#endif
