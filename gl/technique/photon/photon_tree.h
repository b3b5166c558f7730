// The photon tree (section 3.1/3.3): built on the GPU each frame over the photons in the tracer's order
// (PhotonTracer: kd order, or Hilbert order) as a complete binary tree in heap layout, a linear hierarchy
// whose node k of level l holds the photons [floor(k N / 2^l), floor((k + 1) N / 2^l))
// (glsl/technique/photon/photon_tree.glsl). The paper builds a kd-tree after Zhou et al. 2008; over the kd
// order (orderAsKdTree) the nodes are that balanced kd-tree's cells, whose levels 12-13 the cut's E_min is
// taken from. Leaves hold at most leafPhotons photons.
// Per node: bounding box, count, power, centre, mean normal and Eq. 3's estimate E~_p, built by one pass
// for the leaves and one per level above them; timed "photon-tree".
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

// Dispatches `count` invocations of a 64-wide `program` that reads its index from linearInvocation()
// (glsl/technique/photon/linear_dispatch.glsl): groups of 64 in rows (gl/resource/dispatch.h: dispatchRows).
void dispatchLinear(const Program& program, std::uint32_t count);

// std430 mirror of PhotonNode in photon_tree.glsl.
struct GpuPhotonNode {
    glm::vec4 lo;       // w: count
    glm::vec4 hi;       // w: r_p
    glm::vec4 power;    // w: E~_p
    glm::vec4 position; // summed positions, w: summed luminous power
    glm::vec4 normal;
    glm::vec4 incoming;
};
static_assert(sizeof(GpuPhotonNode) == 96);

class PhotonTree {
public:
    explicit PhotonTree(int leafPhotons = 16);

    // photons: `count` photons in kd (or Hilbert) order at SSBO_PHOTONS' layout. minRadius: the smallest r_p (a
    // node of coincident photons has a box of size 0; Eq. 3 divides by r_p^2).
    void build(const Buffer& photons, std::uint32_t count, float minRadius, PassTimers& timers);
    // Binds the nodes at SSBO_PHOTON_NODES and sets photon_tree.glsl's uniforms on `program`.
    void bind(Program& program) const;

    int depth() const { return depth_; }
    std::uint32_t photonCount() const { return count_; }
    std::uint32_t nodeCount() const { return 2u << depth_; } // heap slots, slot 0 unused
    const Buffer& nodes() const { return nodes_; }
    std::vector<GpuPhotonNode> download() const;
    // Node i's photon range (the GLSL's nodeRange), for tests.
    static std::pair<std::uint32_t, std::uint32_t> range(std::uint32_t node, std::uint32_t photons);

private:
    int leafPhotons_;
    int depth_ = 0;
    std::uint32_t count_ = 0;
    float minRadius_ = 0.0f;
    Buffer nodes_;
    Program leaves_, reduce_;
};

} // namespace bounce::gl
