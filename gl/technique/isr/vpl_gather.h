// The full-screen VPL gather (Nichols, Shopf & Wyman 2009, §3.2.2, Eqs. 1 and 5) at every pixel of the
// frame, without the multiresolution stencil: what `rsm`, `rsm-full` and `isr` with multires=0 use. Writes
// frame.indirect(). No indirect visibility (as in the paper).
//
// The VPL cache: a buffer of VPLs (glsl/technique/isr/vpl.glsl) that the sampling and clustering passes
// write as an SSBO and every gather reads through a uniform block of vplsPerBlock() consecutive VPLs,
// one block per draw or dispatch (vpl.glsl says why). Caches are allocated in whole blocks, so that every
// block bound is backed by the buffer.
#pragma once

#include <string>
#include <vector>

#include "gl/frame/frame.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

// VPLs of one uniform block: 1024, or the largest power of two that GL_MAX_UNIFORM_BLOCK_SIZE holds where
// that is smaller (GL 4.5 guarantees 16 KiB: 256 VPLs). A power of two, so block offsets meet any
// GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT up to 16 x the block's VPLs.
int vplsPerBlock();
// VPL_BLOCK_SIZE for the programs that include vpl.glsl to read the cache.
std::vector<Define> vplBlockDefines();
// Bytes of a cache for `vpls` VPLs: whole blocks, at least one.
std::size_t vplCacheBytes(int vpls);
// Makes `cache` hold at least `vpls` VPLs (whole blocks); reallocates (contents lost) only when too small.
void reserveVplCache(Buffer& cache, int vpls);
// Blocks that `count` VPLs fill (0 for none).
int vplBlockCount(int count);
// Binds block `block` of `cache` to vpl.glsl's VplBlock; returns how many of its VPLs are below `count`.
int bindVplBlock(const Buffer& cache, int block, int count);

// vpl.glsl's vplContribution, counted: the offset, two dot products, r^2, Eq. 5's denominator, one
// division and the rgb products and sum (PassCost of every gather).
inline constexpr double kFlopsPerVpl = 38.0;
// The uniform-block words vplContribution reads per VPL: position and area (4), normal (3), flux (3).
inline constexpr double kUniformWordsPerVpl = 10.0;

class VplGather {
public:
    VplGather();
    // Gathers VPLs [0, count) of `vpls` into frame.indirect(), timed as `pass`.
    void gather(Frame& frame, const Buffer& vpls, int count, PassTimers& timers, const std::string& pass = "gather");

private:
    Program program_;
};

} // namespace bounce::gl
