// The VPL tree of hierarchical image-space radiosity (Nichols, Shopf & Wyman 2009, §3.5): the
// full-resolution RSM reorganised each frame into clusters of 2^m x 2^m texels, stored in one flat buffer
// with the whole subtree of each top patch contiguous (layout: glsl/technique/isr/vpl_tree.glsl). Each
// cluster holds the summed reflected flux, solid angle and area of its lit texels, their area-weighted
// mean position and normal, the smallest and largest light distance of its texels (the largest is the
// |V_j| of Eq. 8's bound: a max-mipmap), and whether it spans a light-space discontinuity. Built by one compute pass for the texels and one per level; timed "vpl-tree".
#pragma once

#include <vector>

#include "gl/frame/rsm.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

class VplTree {
public:
    static constexpr int kMaxDepth = 10; // glsl: VPL_TREE_MAX_DEPTH
    static constexpr std::size_t kNodeBytes = 64;

    // topGrid: top patches per side of each view (the paper: 16); at most the RSM size. The thresholds
    // mark clusters that span a light-space discontinuity (glsl/technique/isr/vpl_tree_reduce.comp);
    // huge values mark none (the paper's tree).
    explicit VplTree(int topGrid = 16, float lightDepthThreshold = 0.1f, float lightNormalThreshold = 0.01f);

    // Rebuilds the tree from `rsm` (level 0 of it only; its size must be a power of two).
    void build(const RsmPass& rsm, PassTimers& timers);
    // New light-space discontinuity thresholds for the next build (uniforms of its reduce pass).
    void setThresholds(float lightDepthThreshold, float lightNormalThreshold)
    {
        lightDepthThreshold_ = lightDepthThreshold;
        lightNormalThreshold_ = lightNormalThreshold;
    }
    void bind() const; // the nodes at SSBO_ISR_VPL_TREE (the build passes write them there)
    // The nodes as a buffer texture at UNIT_ISR_VPL_TREE_TEXELS (four RGBA32F texels each): what the gather reads.
    void bindTexels() const;
    // Sets the layout uniforms of glsl/technique/isr/vpl_tree.glsl on `program`.
    void setUniforms(Program& program) const;

    int depth() const { return depth_; }     // T: levels above the texels
    int topGrid() const { return grid_; }    // top patches per side actually used
    int rootCount() const { return roots_; } // views x topGrid^2
    int subtreeNodes() const { return subtreeNodes_; }
    int nodeCount() const { return roots_ * subtreeNodes_; }
    int levelOffset(int m) const { return offsets_.at(std::size_t(m)); }
    const Buffer& nodes() const { return nodes_; }

private:
    int requestedGrid_;
    float lightDepthThreshold_, lightNormalThreshold_;
    int grid_ = 0, depth_ = 0, roots_ = 0, subtreeNodes_ = 0;
    std::vector<int> offsets_;
    Buffer nodes_;
    Texture texels_; // a view of nodes_
    Program leaves_, reduce_;
};

} // namespace bounce::gl
