// The frame's parallel primitives, which the photon family builds on (its paper's section 5: "scan,
// reduction, list compaction, and segmented versions of them") and point projection re-clusters with
// (gl/frame/points/median_split.h), as GL 4.5 compute passes:
//   GpuScan    exclusive prefix sum of a uint array, in place, its total into a counter slot, over all
//              work groups: blocks of 4096 words summed, their sums scanned, each block scanned from its
//              offset;
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
    // The words a work group sums or scans (scan_reduce.comp, scan_blocks.comp: 256 invocations of 16).
    static constexpr std::uint32_t kBlock = 4096;

    GpuScan();
    // data[0..count) := exclusive prefix sums; counters (a uint array) [totalSlot] := the total. Leaves
    // data or its scratch bound as SSBO_SCAN, counters as SSBO_SCAN_TOTALS, its scratch as SSBO_SCAN_SUMS.
    void run(const Buffer& data, std::uint32_t count, const Buffer& counters, std::uint32_t totalSlot);
    // What run() does for `count` words, as per-scope work.
    static PassCost work(std::uint32_t count);
    std::size_t bytes() const { return sums_.bytes(); }

private:
    Program reduce_, blocks_;
    Buffer sums_; // the block sums of every level above the data, one level after another
};

class RadixSort {
public:
    // Each pass splits the keys into runs of at least 32, one invocation each; past maxRuns runs, runs
    // grow. A GPU wants the passes spread over the whole device (kGpuRuns: 32 keys a run up to 8M keys);
    // llvmpipe runs a few SIMD lanes per core and pays for every run's 16 digit counts and their scan
    // (kSoftwareRuns: a 30-bit sort of 1M keys took 188 ms, against 334 ms with kGpuRuns). 0 picks by renderer.
    static constexpr std::uint32_t kGpuRuns = 1u << 18, kSoftwareRuns = 4096;
    explicit RadixSort(std::uint32_t maxRuns = 0);
    // Sorts keys[0..count) ascending by their low `bits` bits (rounded up to a multiple of 8, so that
    // the result ends where it began), carrying values along; equal keys keep their order. keysTmp and
    // valuesTmp are the ping-pong partners, at least count uints each. `counters` receives scan totals
    // at `scratchSlot`.
    void sort(const Buffer& keys, const Buffer& values, const Buffer& keysTmp, const Buffer& valuesTmp,
              std::uint32_t count, int bits, const Buffer& counters, std::uint32_t scratchSlot);
    // What sort() does for `count` pairs and `bits`, as per-scope work (its passes and their scans).
    PassCost work(std::uint32_t count, int bits) const;
    std::size_t bytes() const { return counts_.bytes() + scan_.bytes(); }

private:
    std::uint32_t maxRuns_;
    Program count_, scatter_;
    GpuScan scan_;
    Buffer counts_;
};

} // namespace bounce::gl
