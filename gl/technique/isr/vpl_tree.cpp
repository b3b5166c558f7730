#include "gl/technique/isr/vpl_tree.h"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <string>

#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/technique/isr/bindings.h"

namespace bounce::gl {

VplTree::VplTree(int topGrid, float lightDepthThreshold, float lightNormalThreshold)
    : requestedGrid_(topGrid),
      lightDepthThreshold_(lightDepthThreshold),
      lightNormalThreshold_(lightNormalThreshold),
      leaves_(Program::compute("vpl-tree.leaves", "technique/isr/vpl_tree_leaves.comp")),
      reduce_(Program::compute("vpl-tree.reduce", "technique/isr/vpl_tree_reduce.comp"))
{
    if (topGrid < 1 || !std::has_single_bit(unsigned(topGrid)))
        throw std::invalid_argument("VPL tree: the top grid must be a power of two, not " + std::to_string(topGrid));
}

void VplTree::bind() const
{
    nodes_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_ISR_VPL_TREE);
}

void VplTree::bindTexels() const
{
    texels_.bind(UNIT_ISR_VPL_TREE_TEXELS);
}

void VplTree::setUniforms(Program& program) const
{
    program.set("treeDepth", depth_);
    program.set("treeTopGrid", grid_);
    program.set("treeSubtreeNodes", subtreeNodes_);
    for (int m = 0; m <= depth_; ++m) program.set("treeLevelOffset[" + std::to_string(m) + "]", offsets_[m]);
}

void VplTree::build(const RsmPass& rsm, PassTimers& timers)
{
    PassCost cost; // vpl_tree_leaves/reduce.comp per node: its four children (or RSM texels), one node out
    cost.flops = 60;
    cost.fetches = 4 * 4;
    cost.bytesRead = 4 * 64;
    cost.bytesWritten = 64;
    auto t = timers.scope("vpl-tree", cost);
    const int size = rsm.size();
    if (!std::has_single_bit(unsigned(size)))
        throw std::invalid_argument("VPL tree: the RSM size must be a power of two, not " + std::to_string(size));
    grid_ = std::min(requestedGrid_, size);
    depth_ = std::bit_width(unsigned(size / grid_)) - 1; // log2 of the top patch side
    if (depth_ > kMaxDepth)
        throw std::invalid_argument("VPL tree deeper than " + std::to_string(kMaxDepth) + " levels");
    // Level m of a subtree has 4^(depth - m) nodes; the coarsest level comes first.
    offsets_.assign(std::size_t(depth_) + 1, 0);
    int offset = 0;
    for (int m = depth_; m >= 0; --m) {
        offsets_[m] = offset;
        offset += 1 << (2 * (depth_ - m));
    }
    subtreeNodes_ = offset;
    roots_ = rsm.viewCount() * grid_ * grid_;
    // The leaves over every RSM texel, then one thread per node of each coarser level.
    double expected = roots_ == 0 ? 0.0 : computeInvocations({size, size, rsm.viewCount()}, {8, 8, 1});
    for (int m = 1; m <= depth_ && roots_ > 0; ++m)
        expected += computeInvocations({(1 << (2 * (depth_ - m))) * roots_, 1, 1}, {64, 1, 1});
    t.expectComputes(expected);
    if (roots_ == 0) return;
    const std::size_t bytes = std::size_t(nodeCount()) * kNodeBytes;
    if (!nodes_ || nodes_.bytes() != bytes) {
        nodes_ = Buffer("vpl-tree.nodes", bytes);
        texels_ = Texture::createBufferView("vpl-tree.texels", GL_RGBA32F, nodes_);
    }

    rsm.bind();
    bind();
    setUniforms(leaves_);
    leaves_.set("rsmSize", size);
    leaves_.use();
    glDispatchCompute(GLuint((size + 7) / 8), GLuint((size + 7) / 8), GLuint(rsm.viewCount()));
    setUniforms(reduce_);
    reduce_.set("subtreeCount", roots_);
    reduce_.set("lightDepthThreshold", lightDepthThreshold_);
    reduce_.set("lightNormalThreshold", lightNormalThreshold_);
    reduce_.use();
    for (int m = 1; m <= depth_; ++m) {
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        reduce_.set("level", m);
        const long long threads = (1LL << (2 * (depth_ - m))) * roots_;
        glDispatchCompute(GLuint((threads + 63) / 64), 1, 1);
    }
    // Read back as an SSBO by tests, as a buffer texture by the gather.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

} // namespace bounce::gl
