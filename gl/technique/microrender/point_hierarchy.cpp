#include "gl/technique/microrender/point_hierarchy.h"

#include <stdexcept>
#include <string>

#include "core/point_order.h"
#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/technique/microrender/bindings.h"

namespace bounce::gl {

static_assert(sizeof(GpuMicroNode) == 48, "hierarchy.glsl's MicroNode");

PointHierarchy::PointHierarchy(const PointCloud& cloud)
    : leaves_(cloud.count()),
      glossy_(cloud.glossy()),
      defines_(cloud.defines()),
      leavesProgram_(
          Program::compute("microrender.hierarchyLeaves", "technique/microrender/hierarchy_leaves.comp", defines_)),
      levelProgram_(
          Program::compute("microrender.hierarchyLevel", "technique/microrender/hierarchy_level.comp", defines_))
{
    levels_ = core::exactLog2(std::uint64_t(leaves_));
    if (levels_ < 0)
        throw std::invalid_argument("micro-rendering's hierarchy needs a power-of-two point count, not " +
                                    std::to_string(leaves_));
    // Heap order: node 0 unused, 1 the root, leaves at [n, 2n).
    nodes_ = Buffer("microrender.hierarchy", std::size_t(2 * leaves_) * nodeBytes());
}

void PointHierarchy::bind() const
{
    nodes_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MICRO_NODES);
}

void PointHierarchy::build(const PointCloud& cloud, PassTimers& timers)
{
    // hierarchy_leaves.comp per point and hierarchy_level.comp per interior node: one node written. The rest
    // per scope, the two kernels apart: a leaf reads its surfel and radiance (and glossy lobe), takes a
    // sqrt; an interior node reads its two children and merges their spheres, cones, areas and radiance
    // (and lobes: mergeGlossy).
    const double leaves = leaves_, interior = leaves_ - 1.0;
    PassCost cost;
    cost.bytesWritten = double(nodeBytes());
    cost.bytesFixed = leaves * (32 + 8 + (glossy_ ? 16 : 0)) + interior * 2.0 * double(nodeBytes());
    cost.flopsFixed = leaves * 4 + interior * (glossy_ ? 245 : 125);
    auto t = timers.scope("hierarchy", cost);
    // The leaves, then one dispatch per level of the tree above them, level l's 2^l nodes.
    t.expectComputes(computeInvocations({leaves_, 1, 1}, {64, 1, 1}));
    for (int level = levels_ - 1; level >= 0; --level)
        t.expectComputes(computeInvocations({1 << level, 1, 1}, {64, 1, 1}));
    cloud.bind();
    bind();
    leavesProgram_.set("leafCount", unsigned(leaves_));
    dispatchCompute(leavesProgram_, {leaves_, 1, 1}, {64, 1, 1});
    for (int level = levels_ - 1; level >= 0; --level) {
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        const int first = 1 << level;
        levelProgram_.set("first", unsigned(first));
        dispatchCompute(levelProgram_, {first, 1, 1}, {64, 1, 1});
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

} // namespace bounce::gl
