#include "gl/frame/points/median_split.h"

#include <algorithm>
#include <string>
#include <utility>

#include "gl/frame/points/bindings.h"
#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "glsl/frame/sort_bindings.glsl"

namespace bounce::gl {

namespace {

constexpr int kLocal = 64;

Program stage(const char* name)
{
    return Program::compute(std::string("points.median") + name, "frame/points/median_split.comp",
                            {{"STAGE", std::string("STAGE_") + name}});
}

} // namespace

MedianSplit::MedianSplit()
    : keyPass_(stage("KEYS")),
      sidePass_(stage("SIDE")),
      flagPass_(stage("FLAGS")),
      scatterPass_(stage("SCATTER")),
      permutePass_(stage("PERMUTE"))
{}

int MedianSplit::levels(std::uint32_t count)
{
    int l = 0;
    for (std::uint64_t largest = count; largest >= 2; largest = (largest + 1) / 2) ++l; // the upper half: ceil
    return l;
}

void MedianSplit::reserve(std::uint32_t count)
{
    if (count <= capacity_) return;
    const std::size_t one = std::size_t(count) * 4u, three = 3u * one;
    keys_ = Buffer("points.medianKeys", one);
    values_ = Buffer("points.medianValues", one);
    keysTmp_ = Buffer("points.medianKeysTmp", one);
    valuesTmp_ = Buffer("points.medianValuesTmp", one);
    lists_ = Buffer("points.medianLists", three);
    listsOut_ = Buffer("points.medianListsOut", three);
    sides_ = Buffer("points.medianSides", one);
    scanned_ = Buffer("points.medianScan", three);
    if (!counters_) counters_ = Buffer("points.medianCounters", 4);
    capacity_ = count;
}

const Buffer& MedianSplit::order(const Buffer& positions, std::uint32_t stride, std::uint32_t count)
{
    reserve(std::max(count, 1u));
    if (count == 0) return lists_;
    // The three lists: the points sorted by x, by y, by z; equal coordinates in index order (the sort is
    // stable and starts from the index order).
    for (unsigned axis = 0; axis < 3; ++axis) {
        positions.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MEDIAN_POSITIONS);
        keys_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_KEYS);
        values_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SORT_VALUES);
        keyPass_.set("count", count);
        keyPass_.set("stride", stride);
        keyPass_.set("axis", axis);
        dispatchCompute(keyPass_, {int(count), 1, 1}, {kLocal, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        sort_.sort(keys_, values_, keysTmp_, valuesTmp_, count, 32, counters_, 0);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glCopyNamedBufferSubData(values_.id(), lists_.id(), 0, GLintptr(axis) * count * 4, GLsizeiptr(count) * 4);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    // Each level: every segment's half per point (its longest axis's list), the lower half flagged in every
    // list, the flags scanned, every list's segments partitioned in order.
    for (int level = 0; level < levels(count); ++level) {
        for (Program* p : {&sidePass_, &flagPass_, &scatterPass_}) {
            p->set("count", count);
            p->set("stride", stride);
            p->set("level", level);
        }
        positions.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MEDIAN_POSITIONS);
        lists_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MEDIAN_LISTS);
        listsOut_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MEDIAN_LISTS_OUT);
        sides_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MEDIAN_SIDE);
        scanned_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCAN);
        dispatchCompute(sidePass_, {int(count), 1, 1}, {kLocal, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        dispatchCompute(flagPass_, {int(count), 3, 1}, {kLocal, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        scan_.run(scanned_, 3u * count, counters_, 0);
        scanned_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCAN);
        dispatchCompute(scatterPass_, {int(count), 3, 1}, {kLocal, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        std::swap(lists_, listsOut_);
    }
    return lists_;
}

void MedianSplit::permute(const Buffer& samples, const Buffer& out, std::uint32_t count)
{
    if (count == 0) return;
    lists_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MEDIAN_LISTS);
    samples.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_POINT_SAMPLES);
    out.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MEDIAN_SAMPLES_OUT);
    permutePass_.set("count", count);
    dispatchCompute(permutePass_, {int(count), 1, 1}, {kLocal, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

PassCost MedianSplit::work(std::uint32_t count) const
{
    // KEYS per point and axis: a coordinate read, its bits ordered, a key and an index written; the three
    // sorts. Per level: SIDE reads six list entries and their coordinates and writes a side (the segment
    // found in `level` halvings); FLAGS per list entry reads it and its side and writes a flag; the scan
    // of 3n flags; SCATTER reads an entry, its side and two scanned words and writes the entry. PERMUTE
    // moves 16 bytes per point by its index.
    const double n = count;
    const int l = levels(count);
    PassCost w;
    w.flopsFixed = 3 * n * 4;
    w.bytesFixed = 3 * n * (4 + 8);
    const PassCost sort = sort_.work(count, 32);
    w.flopsFixed += 3 * sort.flopsFixed;
    w.bytesFixed += 3 * (sort.bytesFixed + 8 * n); // the copy of the sorted indices
    const PassCost scan = GpuScan::work(3 * count);
    for (int i = 0; i < l; ++i) {
        w.flopsFixed += n * (3 * i + 12) + 3 * n * (3 * i + 2) + scan.flopsFixed + 3 * n * (3 * i + 8);
        w.bytesFixed += n * (6 * 4 + 6 * 4 + 4) + 3 * n * (4 + 4 + 4) + scan.bytesFixed + 3 * n * (4 + 4 + 8 + 4);
    }
    w.bytesFixed += n * (4 + 16 + 16);
    return w;
}

} // namespace bounce::gl
