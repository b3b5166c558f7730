// Micro-rendering's point hierarchy (Ritschel et al. 2009, §2.1, §3.1) over the shared point cloud: a
// complete binary tree in heap order (glsl/technique/microrender/hierarchy.glsl has the layout), rebuilt on
// the GPU every frame bottom-up: one dispatch for the leaves, one per level ("hierarchy").
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/frame/points/point_cloud.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

// std430 mirror of hierarchy.glsl's MicroNode without its glossy lobe: a cloud with glossy lobes
// (PointCloud::glossy) has 16 bytes more per node (nodeBytes()).
struct GpuMicroNode {
    glm::vec4 sphere;
    glm::vec4 cone;
    std::uint32_t radiance[2];
    float areaM2;
    float pad;
};

class PointHierarchy {
public:
    // The cloud's point count must be a power of two (a complete tree).
    explicit PointHierarchy(const PointCloud& cloud);

    // "hierarchy": leaves from the cloud's surfels and radiance, then the levels bottom-up.
    void build(const PointCloud& cloud, PassTimers& timers);
    void bind() const;

    int leafCount() const { return leaves_; }
    int levels() const { return levels_; } // log2(leafCount): the root is level 0, the leaves level `levels`
    std::size_t nodeBytes() const { return glossy_ ? sizeof(GpuMicroNode) + 16 : sizeof(GpuMicroNode); }
    // The cloud's defines (GLOSSY_POINTS), for every program that reads the nodes.
    const std::vector<Define>& defines() const { return defines_; }
    const Buffer& nodes() const { return nodes_; }

private:
    int leaves_ = 0, levels_ = 0;
    bool glossy_ = false;
    std::vector<Define> defines_;
    Buffer nodes_;
    Program leavesProgram_, levelProgram_;
};

} // namespace bounce::gl
