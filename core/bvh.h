// A bounding volume hierarchy over a core::Scene's triangles, built on the CPU and laid out for the GPU
// (std430 arrays that gl/frame/ray_caster.h uploads as they are and glsl/common/raycast.glsl walks).
//
// Build: binned SAH (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies"):
// kBins centroid bins per axis, leaves of at most kMaxLeafSize triangles, depth at most kMaxDepth.
//
// Layout: a multiple-threaded BVH (MTBVH; Hachisuka 2015, "Implementing a practical rendering system
// using GLSL"): the tree is flattened depth-first six times, once per major ray direction (+x, -x, +y,
// -y, +z, -z), each time with the children of every node in the order a ray along that direction
// meets them. Every node keeps the index of the node after its subtree (its miss link); the node after
// it in the array is its first child. A ray picks the copy of its major direction and walks it with no
// stack: box hit -> next node (or, in a leaf, test its triangles, then the miss link); box missed ->
// the miss link (Smits 1998, "Efficiency issues for ray tracing"). No stack is the point: llvmpipe
// runs every masked iteration of a shader loop on all lanes, and a per-lane stack is a per-lane array.
//
// Intersection: the watertight test of Woop, Benthin & Wald 2013 ("Watertight ray/triangle
// intersection", JCGT 2(1)), without its double-precision fallback: an edge function that is exactly 0
// counts as inside for both triangles sharing the edge, so a ray through an edge or a vertex hits one
// of them (ties go to the one met first). Boxes are tested with Ize's conservative slab test (2013,
// "Robust BVH ray traversal", JCGT 2(2)) so that no box drops a ray its triangles would accept.
//
// Triangles keep their index in the scene's global order (meshes in order, triangles in order: the
// order of gl::GpuScene's index buffer and ref::EmbreeScene::globalTriangle). Triangles that no ray can
// hit (a non-finite vertex, or a cross product of exactly zero: collinear or repeated vertices) are
// left out of the tree.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace bounce::core {

// std430 mirror of BvhNode in glsl/common/raycast.glsl (32 bytes).
struct BvhNode {
    glm::vec3 lo;
    std::int32_t miss; // absolute index of the node after this subtree in this copy; -1 ends the walk
    glm::vec3 hi;
    std::int32_t leaf; // -1: interior (its first child is the next node); else first << 5 | count
};
static_assert(sizeof(BvhNode) == 32);

// std430 mirror of BvhTriangle in glsl/common/raycast.glsl (48 bytes): the vertices as stored in the
// scene, so that two triangles sharing an edge share its float coordinates exactly.
struct BvhTriangle {
    glm::vec3 v0;
    std::uint32_t index; // global triangle index in the scene
    glm::vec3 v1;
    float pad1 = 0.0f;
    glm::vec3 v2;
    float pad2 = 0.0f;
};
static_assert(sizeof(BvhTriangle) == 48);

struct RayHit {
    std::uint32_t triangle = 0; // global index
    float t = 0.0f;
    float b1 = 0.0f, b2 = 0.0f; // p = (1 - b1 - b2) v0 + b1 v1 + b2 v2 (Embree's u, v)
};

// Counts of one walk, for the benchmark's "why": nodes whose box was tested, triangles tested.
struct TraversalStats {
    std::uint64_t nodes = 0;
    std::uint64_t triangles = 0;
};

class Bvh {
public:
    static constexpr int kBins = 16;
    static constexpr int kMaxLeafSize = 4; // the leaf field holds up to 31 (past kMaxDepth)
    static constexpr int kMaxDepth = 48;
    static constexpr int kDirections = 6; // copies of the tree: +x, -x, +y, -y, +z, -z

    Bvh() = default;
    explicit Bvh(const Scene& scene);

    // kDirections copies of nodeCount() nodes; copy d starts at d * nodeCount(). An empty scene has one
    // leaf with no triangles per copy.
    const std::vector<BvhNode>& nodes() const { return nodes_; }
    const std::vector<BvhTriangle>& triangles() const { return triangles_; } // in leaf order
    std::size_t nodeCount() const { return nodes_.size() / kDirections; }
    std::size_t skippedTriangles() const { return skipped_; } // unhittable, left out
    int depth() const { return depth_; }

    // Nearest hit with tMin < t < tMax; the walk of raycast.glsl, step for step.
    bool closestHit(const glm::vec3& origin, const glm::vec3& dir, float tMin, float tMax, RayHit& hit,
                    TraversalStats* stats = nullptr) const;
    // Whether any triangle lies on the ray with tMin < t < tMax.
    bool anyHit(const glm::vec3& origin, const glm::vec3& dir, float tMin, float tMax,
                TraversalStats* stats = nullptr) const;

    // The copy of the tree a ray along dir walks: its major axis and sign (0: +x, 1: -x ... 5: -z).
    static int directionIndex(const glm::vec3& dir);
    // Whether any ray can hit the triangle (finite vertices, non-zero cross product).
    static bool hittable(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2);

private:
    std::vector<BvhNode> nodes_;
    std::vector<BvhTriangle> triangles_;
    std::size_t skipped_ = 0;
    int depth_ = 0;
};

// The precomputed form of one ray for the watertight test (Woop et al. 2013, Sec. 3): the shear that
// takes the ray to the +z axis, written as three rows so the GLSL needs no dynamic component index.
struct WatertightRay {
    glm::vec3 origin;
    glm::vec3 rowX, rowY, rowZ; // A' = (dot(rowX, A), dot(rowY, A), dot(rowZ, A)) for A = vertex - origin
    glm::vec3 invDir;           // for the slab test: 1/dir with zero components replaced by a tiny one
    WatertightRay(const glm::vec3& origin, const glm::vec3& dir);
};

// The watertight test against one triangle, both sides; true with t in (tMin, tMax).
bool intersectTriangle(const WatertightRay& ray, const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2,
                       float tMin, float tMax, float& t, float& b1, float& b2);

} // namespace bounce::core
