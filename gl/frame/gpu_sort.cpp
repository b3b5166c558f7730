#include "gl/frame/gpu_sort.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "gl/context/context.h"
#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "glsl/frame/sort_bindings.glsl"

namespace bounce::gl {

namespace {

// How sort() splits `count` keys: runs of 32 keys, one invocation each, at most maxRuns of them (past
// that, runs grow); the digit counts (16 per run) are a scan over all work groups like any other; two
// 4-bit passes per 8 bits, so that the result ends where it began.
constexpr std::uint32_t kRunLength = 32;

struct SortPasses {
    std::uint32_t runLength, runs;
    int passes;
};

SortPasses sortPasses(std::uint32_t count, int bits, std::uint32_t maxRuns)
{
    const std::uint32_t runLength = std::max(kRunLength, (count + maxRuns - 1) / maxRuns);
    return {runLength, (count + runLength - 1) / runLength, 2 * ((std::clamp(bits, 1, 32) + 7) / 8)};
}

std::uint32_t blockCount(std::uint32_t words)
{
    return (words + GpuScan::kBlock - 1) / GpuScan::kBlock;
}

// The levels of a scan of `count` words: the data, then the block sums of the level below, until one
// block holds a level. Level 0 is the caller's buffer; the others lie one after another in the scratch.
struct ScanLevel {
    std::uint32_t offset, count;
};

std::vector<ScanLevel> scanLevels(std::uint32_t count)
{
    std::vector<ScanLevel> levels{{0, count}};
    std::uint32_t scratch = 0;
    while (levels.back().count > GpuScan::kBlock) {
        levels.push_back({scratch, blockCount(levels.back().count)});
        scratch += levels.back().count;
    }
    return levels;
}

} // namespace

GpuScan::GpuScan()
    : reduce_(Program::compute("frame.scanReduce", "frame/scan_reduce.comp")),
      blocks_(Program::compute("frame.scanBlocks", "frame/scan_blocks.comp"))
{}

void GpuScan::run(const Buffer& data, std::uint32_t count, const Buffer& counters, std::uint32_t totalSlot)
{
    const std::vector<ScanLevel> levels = scanLevels(count);
    const std::size_t top = levels.size() - 1;
    // At least one word, so that the block-sums slot is bound even when one block holds the data.
    const std::size_t scratchBytes =
        4u * std::max<std::size_t>(1, levels[top].offset + (top > 0 ? levels[top].count : 0));
    if (!sums_ || sums_.bytes() < scratchBytes) sums_ = Buffer("frame.scanSums", scratchBytes);
    counters.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCAN_TOTALS);
    sums_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCAN_SUMS);
    // One pass over level i's blocks; the level above (i + 1) holds their sums.
    auto pass = [&](Program& p, std::size_t i) {
        (i == 0 ? data : sums_).bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCAN);
        const std::uint32_t blocks = std::max(1u, blockCount(levels[i].count)); // no words: one block, total 0
        p.set("dataOffset", levels[i].offset);
        p.set("count", levels[i].count);
        p.set("blocks", blocks);
        p.set("sumsOffset", i < top ? levels[i + 1].offset : 0u);
        dispatchRows(p, blocks, 256);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    };
    // Up: every level below the top summed block by block into the level above.
    for (std::size_t i = 0; i < top; ++i) pass(reduce_, i);
    // The top level (one block) scanned, its total written; then down, each level scanned from the
    // scanned sums of its blocks.
    blocks_.set("totalSlot", totalSlot);
    for (std::size_t i = top + 1; i-- > 0;) {
        blocks_.set("topLevel", int(i == top));
        pass(blocks_, i);
    }
}

PassCost GpuScan::work(std::uint32_t count)
{
    // Per level of n words below the top: scan_reduce.comp reads them and sums 256 partial sums per block
    // in a tree of shared memory, writing one word per block. Per level: scan_blocks.comp reads and writes
    // them and scans 256 sums per block in 8 steps of shared memory (a read, an add and a write each).
    PassCost w;
    const std::vector<ScanLevel> levels = scanLevels(count);
    for (std::size_t i = 0; i < levels.size(); ++i) {
        const double n = levels[i].count, blocks = std::max(1u, blockCount(levels[i].count));
        w.flopsFixed += 2.0 * n + blocks * 256.0 * 8 * 2;
        w.bytesFixed += 8.0 * n + (i + 1 < levels.size() ? 4.0 * blocks : 4.0);
        if (i + 1 < levels.size()) {
            w.flopsFixed += n + blocks * 256.0;
            w.bytesFixed += 4.0 * n + 4.0 * blocks;
        }
    }
    return w;
}

RadixSort::RadixSort(std::uint32_t maxRuns)
    : maxRuns_(maxRuns > 0            ? maxRuns
               : softwareRasterizer() ? kSoftwareRuns
                                      : kGpuRuns),
      count_(Program::compute("frame.radixCount", "frame/radix_count.comp")),
      scatter_(Program::compute("frame.radixScatter", "frame/radix_scatter.comp"))
{}

void RadixSort::sort(const Buffer& keys, const Buffer& values, const Buffer& keysTmp, const Buffer& valuesTmp,
                     std::uint32_t count, int bits, const Buffer& counters, std::uint32_t scratchSlot)
{
    if (count == 0) return;
    if (keys.bytes() < count * 4u || values.bytes() < count * 4u || keysTmp.bytes() < count * 4u ||
        valuesTmp.bytes() < count * 4u)
        throw std::logic_error("RadixSort: buffers smaller than the count");
    const auto [runLength, runs, passes] = sortPasses(count, bits, maxRuns_);
    const std::size_t countBytes = std::size_t(runs) * 16u * 4u;
    if (!counts_ || counts_.bytes() < countBytes) counts_ = Buffer("frame.sortCounts", countBytes);
    for (int pass = 0; pass < passes; ++pass) {
        const bool even = pass % 2 == 0;
        const Buffer& kIn = even ? keys : keysTmp;
        const Buffer& vIn = even ? values : valuesTmp;
        const Buffer& kOut = even ? keysTmp : keys;
        const Buffer& vOut = even ? valuesTmp : values;
        kIn.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_KEYS);
        vIn.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_VALUES);
        kOut.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_KEYS_OUT);
        vOut.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_VALUES_OUT);
        counts_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_COUNTS);
        for (Program* p : {&count_, &scatter_}) {
            p->set("count", count);
            p->set("runLength", runLength);
            p->set("runs", runs);
            p->set("shift", unsigned(4 * pass));
        }
        dispatchCompute(count_, {int(runs), 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        scan_.run(counts_, runs * 16u, counters, scratchSlot);
        dispatchCompute(scatter_, {int(runs), 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

PassCost RadixSort::work(std::uint32_t count, int bits) const
{
    if (count == 0) return {};
    // Per pass: radix_count.comp reads every key (its digit counted: 3 operations) and writes 16 counts per
    // run; the scan of the counts; radix_scatter.comp reads a run's 16 counts, then moves every key and
    // value (4 bytes each, read and written) to its digit's next slot.
    const auto [runLength, runs, passes] = sortPasses(count, bits, maxRuns_);
    const PassCost scan = GpuScan::work(runs * 16u);
    PassCost w;
    w.flopsFixed = passes * (6.0 * count + scan.flopsFixed);
    w.bytesFixed = passes * ((4.0 + 16.0) * count + 2.0 * 64 * runs + scan.bytesFixed);
    return w;
}

} // namespace bounce::gl
