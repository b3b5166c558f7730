#include "gl/technique/photon/illumination_cut.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/technique/photon/bindings.h"
#include "gl/technique/photon/photon_tracer.h"

namespace bounce::gl {

PassCost nearestPhotonsWork(const PhotonTree& tree, int k, double searches)
{
    // density.glsl per search: about 2 x depth nodes (96 bytes, a box distance each) and 2k photons
    // examined (64 bytes: a distance, the normal test, the heap of k), then the k found read for their sums.
    const double nodes = 2.0 * std::max(tree.depth(), 1);
    PassCost w;
    w.flopsFixed = searches * (15 * nodes + 35 * 2.0 * k + 15.0 * k);
    w.bytesFixed = searches * (sizeof(GpuPhotonNode) * nodes + 64 * 3.0 * k);
    return w;
}

IlluminationCut::IlluminationCut()
    : emin_(Program::compute("photon.cutEmin", "technique/photon/cut_emin.comp")),
      select_(Program::compute("photon.cutSelect", "technique/photon/cut_select.comp")),
      mark_(Program::compute("photon.cutMark", "technique/photon/cut_mark.comp")),
      flags_(Program::compute("photon.cutFlags", "technique/photon/cut_flags.comp")),
      listProgram_(Program::compute("photon.cutList", "technique/photon/cut_list.comp")),
      enter_(Program::compute("photon.cutEnter", "technique/photon/cut_enter.comp")),
      influence_(Program::compute("photon.cutInfluence", "technique/photon/cut_influence.comp"))
{}

void IlluminationCut::bind() const
{
    nodes_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_CUT);
}

void IlluminationCut::useGrid(const core::Bounds& domain, int cells)
{
    gridCells_ = 0;
    gridDims_ = glm::ivec3(0);
    cells = std::min(cells, kMaxGridCells);
    if (cells <= 0 || domain.empty()) return;
    // A flat or thin scene's grid keeps a thickness of a thousandth of its largest side.
    const glm::vec3 e = domain.extent();
    const glm::vec3 extent = glm::max(e, glm::vec3(1e-3f * std::max({e.x, e.y, e.z, 1e-30f})));
    float side = std::cbrt(extent.x * extent.y * extent.z / float(cells));
    for (;;) { // a side shorter than one cell still takes one: widen the cells until they fit
        gridDims_ = glm::max(glm::ivec3(glm::floor(extent / side)), glm::ivec3(1));
        if (gridDims_.x * gridDims_.y * gridDims_.z <= cells) break;
        side *= 1.05f;
    }
    // The cells cover the domain: its far side falls in the last cell, which the clamp stretches.
    gridOrigin_ = domain.lo;
    gridInverseCell_ = 1.0f / side;
    gridCells_ = std::uint32_t(gridDims_.x * gridDims_.y * gridDims_.z);
    if (!gridCount_) {
        gridCount_ = Program::compute("photon.cutGridCount", "technique/photon/cut_grid_cells.comp");
        gridFill_ = Program::compute("photon.cutGridFill", "technique/photon/cut_grid_cells.comp", {{"FILL", "1"}});
        gridSort_ = Program::compute("photon.cutGridSort", "technique/photon/cut_grid_sort.comp");
    }
}

void IlluminationCut::setGridUniforms(Program& p) const
{
    p.set("cutGridOrigin", gridOrigin_);
    p.set("cutGridInverseCell", gridInverseCell_);
    p.set("cutGridDims", gridDims_);
    p.set("cutGridCapacity", std::uint32_t(grid_.bytes() / 4 - (gridCells_ + 2)));
}

void IlluminationCut::bindLookup(Program& program) const
{
    bind();
    if (gridCells_ == 0) return;
    grid_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CUT_GRID);
    setGridUniforms(program);
}

bool IlluminationCut::gridUsable() const
{
    if (gridCells_ == 0 || !grid_) return false;
    std::uint32_t words[2] = {0, 0}; // the total, the flag of a list too long to sort
    grid_.download(std::size_t(gridCells_) * 4, sizeof words, words);
    return words[0] <= grid_.bytes() / 4 - (gridCells_ + 2) && words[1] == 0;
}

void IlluminationCut::buildGrid(Buffer& counters, PassTimers::Scope& t)
{
    // The cells' starts, the flag word, and room for the lists kept from the last frame.
    const std::size_t startBytes = (std::size_t(gridCells_) + 2) * 4;
    if (!grid_ || grid_.bytes() < startBytes) grid_ = Buffer("photon.cutGrid", startBytes);
    if (!gridCursors_ || gridCursors_.bytes() != std::size_t(gridCells_) * 4)
        gridCursors_ = Buffer("photon.cutGridCursors", std::size_t(gridCells_) * 4);
    // Only the starts and the flag: the lists' words are all written by the fill before anything reads them.
    const unsigned zero = 0;
    glClearNamedBufferSubData(grid_.id(), GL_R32UI, 0, GLsizeiptr(startBytes), GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    gridCursors_.clearToZero();
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    auto run = [&](Program& p, std::uint32_t count) {
        bind();
        grid_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CUT_GRID);
        gridCursors_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CUT_GRID_CURSORS);
        setGridUniforms(p);
        p.set("nodeCount", nodeCount_);
        dispatchLinear(p, count);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    };
    // Every cut node's kernel over its cells, counted; the counts scanned into starts (the scan's last
    // word, an empty count, becomes the total).
    run(gridCount_, nodeCount_);
    scan_.run(grid_, gridCells_ + 1, counters, kCounterScratch);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    counters.download(kCounterScratch * 4, 4, &gridEntries_);
    // Room for the lists, grown with a quarter to spare (so that small changes do not reallocate), the
    // starts copied over.
    if (grid_.bytes() < startBytes + std::size_t(gridEntries_) * 4) {
        Buffer grown("photon.cutGrid", startBytes + (std::size_t(gridEntries_) + gridEntries_ / 4) * 4);
        glCopyNamedBufferSubData(grid_.id(), grown.id(), 0, 0, GLsizeiptr(startBytes));
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        grid_ = std::move(grown);
    }
    run(gridFill_, nodeCount_);
    run(gridSort_, gridCells_);
    // cut_grid_cells.comp twice per heap slot: its flags and, in the cut, its kernel read, then per entry an
    // atomic (and, filling, the cell's start read and the entry written); the scan of the cells; per cell
    // its start and end read, its list heapsorted (about 2 log2 of its length reads and writes per entry).
    const double entries = gridEntries_, perCell = entries / std::max(gridCells_, 1u);
    t.addWork(kernelWork(nodeCount_, {.flops = 30, .bytesRead = 4 + 16}));
    t.addWork(kernelWork(entries, {.flops = 8, .bytesRead = 4, .bytesWritten = 4}));
    t.addWork(GpuScan::work(gridCells_ + 1));
    t.addWork(kernelWork(nodeCount_, {.flops = 30, .bytesRead = 4 + 16}));
    t.addWork(kernelWork(entries, {.flops = 8, .bytesRead = 12, .bytesWritten = 8}));
    t.addWork(kernelWork(gridCells_, {.flops = 10, .bytesRead = 8}));
    t.addWork(kernelWork(entries, {.flops = 10 * std::log2(perCell + 2.0),
                                   .bytesRead = 16 * std::log2(perCell + 2.0),
                                   .bytesWritten = 8 * std::log2(perCell + 2.0)}));
}

std::uint32_t IlluminationCut::compact(const PhotonTree& tree, Buffer& counters, PassTimers::Scope& t)
{
    // cut_flags.comp per node: its flags read, its mark written; the scan of the marks; cut_list.comp per
    // node: its flags read and, in the cut, its position read and its index written.
    t.addWork(kernelWork(nodeCount_, {.flops = 3, .bytesRead = 4, .bytesWritten = 4}));
    t.addWork(GpuScan::work(nodeCount_));
    t.addWork(kernelWork(nodeCount_, {.flops = 3, .bytesRead = 8, .bytesWritten = 4}));
    bind();
    marks_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCAN);
    tree.bind(flags_);
    flags_.set("nodeCount", nodeCount_);
    dispatchLinear(flags_, nodeCount_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    scan_.run(marks_, nodeCount_, counters, kCounterCutSize);
    bind();
    marks_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCAN);
    list_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_CUT_LIST);
    tree.bind(listProgram_);
    listProgram_.set("nodeCount", nodeCount_);
    dispatchLinear(listProgram_, nodeCount_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    std::uint32_t size = 0;
    counters.download(kCounterCutSize * 4, 4, &size);
    return size;
}

void IlluminationCut::build(const PhotonTree& tree, const Buffer& photons, const IlluminationCutSettings& s,
                            Buffer& counters, PassTimers& timers)
{
    auto t = timers.scope("cut");
    nodeCount_ = tree.nodeCount();
    const std::size_t bytes = std::size_t(nodeCount_) * sizeof(GpuCutNode);
    if (!nodes_ || nodes_.bytes() < bytes) {
        nodes_ = Buffer("photon.cutNodes", bytes);
        list_ = Buffer("photon.cutList", std::size_t(nodeCount_) * 2 * 4); // two lists: one read, one written
        marks_ = Buffer("photon.cutMarks", std::size_t(nodeCount_) * 4);
    }
    splits_.clear();
    counters.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_COUNTERS);
    tree.bind(emin_);
    emin_.set("firstLevel", s.eminLevel);
    dispatchCompute(emin_, {256, 1, 1}, {256, 1, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    counters.download(kCounterEmin * 4, 4, &eMin_);

    bind();
    tree.bind(select_);
    const int firstLevel = std::clamp(s.eminLevel, 0, std::max(tree.depth() - 1, 0));
    const int lastLevel = std::min(firstLevel + 1, tree.depth());
    select_.set("lastLevel", lastLevel);
    // Every kernel's work from the counts known here (the tree's nodes: its heap slots less slot 0).
    // cut_emin.comp: the nodes of E_min's two levels (96 bytes each), then its 256 invocations' reduction;
    // cut_select.comp per node: the node, its children's flags and E_min read, its centre, normal and
    // incoming direction, six vec4 written; cut_mark.comp per node: its, its parent's flags and its photon
    // count read, its flags written.
    const double nodes = double(nodeCount_) - 1;
    t.addWork(kernelWork(double((2u << lastLevel) - (1u << firstLevel)), {.flops = 2, .bytesRead = 96}));
    t.addWork(kernelWork(256, {.flops = 16}));
    t.addWork(kernelWork(nodes, {.flops = 40, .bytesRead = 96 + 8, .bytesWritten = 96, .uniformWords = 1}));
    t.addWork(kernelWork(nodes, {.flops = 6, .bytesRead = 12, .bytesWritten = 4}));
    for (int level = tree.depth(); level >= 0; --level) {
        select_.set("level", level);
        dispatchLinear(select_, 1u << level);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    tree.bind(mark_);
    mark_.set("nodeCount", nodeCount_);
    dispatchLinear(mark_, nodeCount_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

    if (!refine_ || refineK_ != s.densityPhotons) {
        refine_ = Program::compute("photon.cutRefine", "technique/photon/cut_refine.comp",
                                   {{"NEAREST_K", std::to_string(s.densityPhotons)}});
        refineK_ = s.densityPhotons;
    }
    // The coarse cut, compacted in heap order; then each iteration refines only the nodes that entered
    // the cut in the one before (cut_refine.comp), and lists the children it sends in (cut_enter.comp):
    // the others have passed or are leaves. The lists alternate between the two halves of list_.
    size_ = compact(tree, counters, t);
    coarseSize_ = size_;
    std::uint32_t entering = size_, offset = 0, next = nodeCount_;
    for (int iteration = 0; iteration <= s.iterations && entering > 0; ++iteration) {
        const bool split = iteration < s.iterations;
        const std::uint32_t zero = 0;
        counters.update(kCounterCutSplits * 4, 4, &zero);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        bind();
        photons.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTONS);
        list_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_CUT_LIST);
        marks_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCAN);
        counters.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_COUNTERS);
        tree.bind(refine_);
        refine_.set("listOffset", offset);
        refine_.set("enteringCount", entering);
        refine_.set("threshold", s.threshold);
        refine_.set("split", split ? 1 : 0);
        refine_.set("iteration", unsigned(iteration + 1));
        dispatchCompute(refine_, {int(entering), 1, 1}, {64, 1, 1});
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        // cut_refine.comp per entering node: its list entry, node and flags read, its k nearest photons
        // searched, E_p, its ratio and its count of children written.
        t.addWork(kernelWork(entering, {.flops = 5, .bytesRead = 4 + 96 + 8, .bytesWritten = 4}));
        t.addWork(nearestPhotonsWork(tree, s.densityPhotons, entering));
        t.addWork(kernelWork(entering, {.flops = 30, .bytesWritten = 24}));
        if (!split) break;
        std::uint32_t splits = 0;
        counters.download(kCounterCutSplits * 4, 4, &splits);
        splits_.push_back(splits);
        // Per split: the node's flags and the counter written, its children's photon counts and flags read,
        // their flags and generations written.
        t.addWork(kernelWork(splits, {.bytesRead = 16, .bytesWritten = 4 + 4 + 16}));
        if (splits == 0) break; // nothing changed: nothing new to evaluate
        // The children counts scanned into positions; cut_enter.comp per entering node: its list entry and
        // flags read, and where it split, its position, its children's photon counts read and their indices
        // written.
        scan_.run(marks_, entering, counters, kCounterCutSize);
        t.addWork(GpuScan::work(entering));
        t.addWork(kernelWork(entering, {.flops = 4, .bytesRead = 8}));
        t.addWork(kernelWork(splits, {.bytesRead = 4 + 8, .bytesWritten = 8}));
        bind();
        marks_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCAN);
        list_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_CUT_LIST);
        tree.bind(enter_);
        enter_.set("listOffset", offset);
        enter_.set("enteringCount", entering);
        enter_.set("nextOffset", next);
        dispatchLinear(enter_, entering);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        std::uint32_t entered = 0;
        counters.download(kCounterCutSize * 4, 4, &entered);
        size_ += entered - splits; // each split node left the cut, its children entered it
        entering = entered;
        std::swap(offset, next);
    }

    // cut_influence.comp per node: its flags and its kernel, or its children's four boxes (128 bytes, the
    // larger), read; its boxes written.
    t.addWork(kernelWork(nodes, {.flops = 12, .bytesRead = 4 + 128, .bytesWritten = 56}));
    bind();
    tree.bind(influence_);
    for (int level = tree.depth(); level >= 0; --level) {
        influence_.set("level", level);
        dispatchLinear(influence_, 1u << level);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    if (gridCells_ > 0) buildGrid(counters, t);
}

std::vector<GpuCutNode> IlluminationCut::download() const
{
    std::vector<GpuCutNode> n = nodes_.download<GpuCutNode>();
    n.resize(nodeCount_);
    return n;
}

std::vector<std::uint32_t> IlluminationCut::downloadList(const PhotonTree& tree, Buffer& counters)
{
    PassTimers timers;
    auto t = timers.scope("cut");
    counters.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_COUNTERS);
    const std::uint32_t size = compact(tree, counters, t);
    std::vector<std::uint32_t> l = list_.download<std::uint32_t>();
    l.resize(size);
    return l;
}

} // namespace bounce::gl
