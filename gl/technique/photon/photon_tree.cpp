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
    auto t = timers.scope("photon-tree");
    count_ = count;
    minRadius_ = minRadius;
    // The least depth whose leaves hold at most leafPhotons photons.
    depth_ = 0;
    while ((std::uint64_t(count) + (1ull << depth_) - 1) >> depth_ > std::uint64_t(leafPhotons_)) ++depth_;
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
