// The median-split order of core/point_order.h (every level, each segment split along its longest axis,
// ties by index) computed on the GPU: point projection re-clusters its points there when the scene is
// manipulated, as its paper does ("each level of split on the GPU using a segmented global sort", Maletz,
// Wang & Bowers 2011, §4). The points are sorted once along each axis by the frame's radix sort
// (gl/frame/gpu_sort.h); each level then partitions every segment of the three sorted lists around the
// median of its longest axis, keeping their order (a flag, the frame's scan, a scatter): the order the
// paper's per-level segmented sort leaves, for the work of a scan per level. The result is core's order
// to the point (MedianSplitTest), the CPU's one-thread median splits its independent twin.
#pragma once

#include <cstdint>

#include "gl/frame/gpu_sort.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

class MedianSplit {
public:
    MedianSplit();
    // The order of `count` points whose coordinates are positions[i * stride + 0..2] (floats): the first
    // count uints of the returned buffer, valid until the next call.
    const Buffer& order(const Buffer& positions, std::uint32_t stride, std::uint32_t count);
    // samples[0..count) (16 bytes each) permuted by the last order(), into `out`.
    void permute(const Buffer& samples, const Buffer& out, std::uint32_t count);
    // The levels order() runs for `count` points: until no segment has two points.
    static int levels(std::uint32_t count);
    // What order() and permute() do for `count` points, as per-scope work.
    PassCost work(std::uint32_t count) const;

private:
    Program keyPass_, sidePass_, flagPass_, scatterPass_, permutePass_;
    RadixSort sort_;
    GpuScan scan_;
    Buffer keys_, values_, keysTmp_, valuesTmp_, lists_, listsOut_, sides_, scanned_, counters_;
    std::uint32_t capacity_ = 0;
    void reserve(std::uint32_t count);
};

} // namespace bounce::gl
