#include "gl/technique/photon/illumination_cut.h"

#include <algorithm>
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

std::uint32_t IlluminationCut::compact(const PhotonTree& tree, Buffer& counters, PassTimers::Scope& t)
{
    // cut_flags.comp per node: its flags read, its mark written; the scan of the marks; cut_list.comp per
    // node: its flags read and, in the cut, its position read and its index written.
    t.addWork(kernelWork(nodeCount_, {.flops = 3, .bytesRead = 4, .bytesWritten = 4}));
    t.addWork(GpuScan::work(nodeCount_));
    t.addWork(kernelWork(nodeCount_, {.flops = 3, .bytesRead = 8, .bytesWritten = 4}));
    bind();
    marks_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_SCAN);
    tree.bind(flags_);
    flags_.set("nodeCount", nodeCount_);
    dispatchLinear(flags_, nodeCount_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    scan_.run(marks_, nodeCount_, counters, kCounterCutSize);
    bind();
    marks_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_SCAN);
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
        marks_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_SCAN);
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
        marks_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_SCAN);
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
