#include "gl/technique/photon/photon_tree.h"

#include <algorithm>
#include <bit>

#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/technique/photon/bindings.h"

namespace bounce::gl {

void dispatchLinear(const Program& program, std::uint32_t count)
{
    dispatchRows(program, std::max<std::size_t>((std::size_t(count) + 63) / 64, 1), 64);
}

PhotonTree::PhotonTree(int leafPhotons)
    : leafPhotons_(std::max(leafPhotons, 1)),
      leaves_(Program::compute("photon.treeLeaves", "technique/photon/tree_leaves.comp")),
      reduce_(Program::compute("photon.treeReduce", "technique/photon/tree_reduce.comp"))
{}

std::pair<std::uint32_t, std::uint32_t> PhotonTree::range(std::uint32_t node, std::uint32_t photons)
{
    const int l = std::bit_width(node) - 1;
    const std::uint64_t k = node - (1u << l);
    return {std::uint32_t((k * photons) >> l), std::uint32_t(((k + 1) * photons) >> l)};
}

void PhotonTree::bind(Program& program) const
{
    nodes_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_NODES);
    program.set("treeDepth", depth_);
    program.set("treePhotons", count_);
    program.set("treeMinRadius", minRadius_);
}

void PhotonTree::build(const Buffer& photons, std::uint32_t count, float minRadius, PassTimers& timers)
{
    // tree_leaves.comp and tree_reduce.comp per node: its sums finished (r_p, the mean normal, Eq. 3's
    // estimate) and the node written; what each kernel reads is added below.
    PassCost cost;
    cost.flops = 25;
    cost.bytesWritten = sizeof(GpuPhotonNode);
    auto t = timers.scope("photon-tree", cost);
    count_ = count;
    minRadius_ = minRadius;
    // The least depth whose leaves hold at most leafPhotons photons.
    depth_ = 0;
    while ((std::uint64_t(count) + (1ull << depth_) - 1) >> depth_ > std::uint64_t(leafPhotons_)) ++depth_;
    // The leaves read every photon once (64 bytes: its luminance, box and weighted sums, 31 flops); each
    // node above them reads its two children (20 flops).
    const double inner = double((1u << depth_) - 1);
    PassCost reads;
    reads.flopsFixed = 31.0 * count + 20.0 * inner;
    reads.bytesFixed = 64.0 * count + 2.0 * sizeof(GpuPhotonNode) * inner;
    t.addWork(reads);
    const std::size_t bytes = std::size_t(nodeCount()) * sizeof(GpuPhotonNode);
    if (!nodes_ || nodes_.bytes() < bytes) nodes_ = Buffer("photon.treeNodes", bytes);
    photons.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTONS);
    bind(leaves_);
    dispatchLinear(leaves_, 1u << depth_);
    bind(reduce_);
    for (int level = depth_ - 1; level >= 0; --level) {
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        reduce_.set("level", level);
        dispatchLinear(reduce_, 1u << level);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

std::vector<GpuPhotonNode> PhotonTree::download() const
{
    std::vector<GpuPhotonNode> n = nodes_.download<GpuPhotonNode>();
    n.resize(nodeCount());
    return n;
}

} // namespace bounce::gl
