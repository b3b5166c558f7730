// The parallel primitives the photon family builds on (the paper's section 5: "scan, reduction, list
// compaction, and segmented versions of them"), as GL 4.5 compute passes:
//   GpuScan    exclusive prefix sum of a uint array, in place, its total into a counter slot;
//   RadixSort  stable LSD radix sort of (key, value) uint pairs, 4 bits per pass.
// Both are deterministic: integer sums, and a scatter that walks contiguous runs in order. Each gives the
// work of a run (work()) for the timed scope that runs it (PassTimers::Scope::addWork).
#pragma once

#include <cstdint>

#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

class GpuScan {
public:
    GpuScan();
    // data[0..count) := exclusive prefix sums; counters (a uint array) [totalSlot] := the total.
    void run(const Buffer& data, std::uint32_t count, const Buffer& counters, std::uint32_t totalSlot);
    // What run() does for `count` words, as per-scope work.
    static PassCost work(std::uint32_t count);

private:
    Program program_;
};

class RadixSort {
public:
    RadixSort();
    // Sorts keys[0..count) ascending by their low `bits` bits (rounded up to a multiple of 8, so that
    // the result ends where it began), carrying values along; equal keys keep their order. keysTmp and
    // valuesTmp are the ping-pong partners, at least count uints each. `counters` receives scan totals
    // at `scratchSlot`.
    void sort(const Buffer& keys, const Buffer& values, const Buffer& keysTmp, const Buffer& valuesTmp,
              std::uint32_t count, int bits, const Buffer& counters, std::uint32_t scratchSlot);
    // What sort() does for `count` pairs and `bits`, as per-scope work (its passes and their scans).
    static PassCost work(std::uint32_t count, int bits);
    std::size_t bytes() const { return counts_.bytes(); }

private:
    Program count_, scatter_;
    GpuScan scan_;
    Buffer counts_;
};

} // namespace bounce::gl
