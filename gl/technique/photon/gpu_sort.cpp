#include "gl/technique/photon/gpu_sort.h"

#include <algorithm>
#include <stdexcept>

#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/technique/photon/bindings.h"

namespace bounce::gl {

namespace {

// How sort() splits `count` keys: runs of at least 32 keys, at most 4096 runs, so that the digit counts
// (16 per run) stay a small scan; two 4-bit passes per 8 bits, so that the result ends where it began.
struct SortPasses {
    std::uint32_t runLength, runs;
    int passes;
};

SortPasses sortPasses(std::uint32_t count, int bits)
{
    const std::uint32_t runLength = std::max<std::uint32_t>(32u, (count + 4095u) / 4096u);
    return {runLength, (count + runLength - 1) / runLength, 2 * ((std::clamp(bits, 1, 32) + 7) / 8)};
}

} // namespace

GpuScan::GpuScan() : program_(Program::compute("photon.scan", "technique/photon/scan.comp"))
{}

void GpuScan::run(const Buffer& data, std::uint32_t count, const Buffer& counters, std::uint32_t totalSlot)
{
    data.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_SCAN);
    counters.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_COUNTERS);
    program_.set("count", count);
    program_.set("totalSlot", totalSlot);
    program_.use();
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

PassCost GpuScan::work(std::uint32_t count)
{
    // scan.comp: its 1024 invocations read their runs of the words twice (the run's sum, then its prefix
    // sums) and write them once, and scan the 1024 run sums in 10 steps of shared memory; one word out.
    PassCost w;
    w.flopsFixed = 2.0 * count + 1024.0 * 10 * 2;
    w.bytesFixed = 12.0 * count + 4;
    return w;
}

RadixSort::RadixSort()
    : count_(Program::compute("photon.radixCount", "technique/photon/radix_count.comp")),
      scatter_(Program::compute("photon.radixScatter", "technique/photon/radix_scatter.comp"))
{}

void RadixSort::sort(const Buffer& keys, const Buffer& values, const Buffer& keysTmp, const Buffer& valuesTmp,
                     std::uint32_t count, int bits, const Buffer& counters, std::uint32_t scratchSlot)
{
    if (count == 0) return;
    if (keys.bytes() < count * 4u || values.bytes() < count * 4u || keysTmp.bytes() < count * 4u ||
        valuesTmp.bytes() < count * 4u)
        throw std::logic_error("RadixSort: buffers smaller than the count");
    const auto [runLength, runs, passes] = sortPasses(count, bits);
    const std::size_t countBytes = std::size_t(runs) * 16u * 4u;
    if (!counts_ || counts_.bytes() < countBytes) counts_ = Buffer("photon.sortCounts", countBytes);
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
        counts_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_COUNTS);
        dispatchCompute(scatter_, {int(runs), 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

PassCost RadixSort::work(std::uint32_t count, int bits)
{
    if (count == 0) return {};
    // Per pass: radix_count.comp reads every key (its digit counted: 3 operations) and writes 16 counts per
    // run; the scan of the counts; radix_scatter.comp reads a run's 16 counts, then moves every key and
    // value (4 bytes each, read and written) to its digit's next slot.
    const auto [runLength, runs, passes] = sortPasses(count, bits);
    const PassCost scan = GpuScan::work(runs * 16u);
    PassCost w;
    w.flopsFixed = passes * (6.0 * count + scan.flopsFixed);
    w.bytesFixed = passes * ((4.0 + 16.0) * count + 2.0 * 64 * runs + scan.bytesFixed);
    return w;
}

} // namespace bounce::gl
