// Shading clusters (Wang et al. 2009, section 3.2): the shading points (the G-buffer's pixels with
// geometry) partitioned into about K coherent clusters on the GPU, each with one irradiance sample:
//   1. a static screen-space quadtree of the shading points, with each node's geometric variation eps_q
//      (Eq. 2 summed over its members around their mean) (quad_*.comp);
//   2. K seeds placed top-down over it in proportion to eps_q, one seed per node jittered over its
//      members (seed_*.comp);
//   3. k-means: every point to its nearest centre by Eq. 2 through a tree of the centres (point_*.comp,
//      kmeans_assign.comp), the points sorted by cluster and each centre set to its segment's mean
//      position and normal (kmeans_segments.comp, kmeans_update.comp): deterministic sums;
//   4. each cluster's sample: the member nearest its centre (kmeans_sample.comp);
//   5. temporal reuse: next frame, the previous centres classify the new points within each cluster's
//      largest member error; clusters without points are eliminated, and new seeds are placed over the
//      points no cluster took, so that about K clusters remain (kmeans_marks/survivors.comp); k-means
//      then moves only the new clusters (the kept centres stay fixed).
// alpha is in units of 1 / (scene size): Eq. 2 is the same for the same scene at any scale.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/frame/frame.h"
#include "gl/frame/gpu_sort.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

// std430 mirror of Cluster in shading_clusters.glsl.
struct GpuCluster {
    glm::vec4 centre; // w: members
    glm::vec4 normal; // w: largest member error
    glm::vec4 sample; // w: sample pixel, or -1
    glm::vec4 sampleNormal;
    glm::vec4 irradiance; // w: R_j
    glm::uvec4 members;
};
static_assert(sizeof(GpuCluster) == 96);
struct GpuPointNode {
    glm::vec4 lo, hi;
    glm::uvec4 normals; // the box of the points' normals, half floats (cluster_point_tree.glsl)
};
// std430 mirror of QuadNode in cluster_quadtree.glsl: a node of the seeding quadtree.
struct GpuQuadNode {
    glm::vec4 position; // xyz summed member positions, w: members
    glm::vec4 normal;   // xyz summed member normals, w: eps_q
};
inline constexpr std::uint32_t kNoCluster = 0xFFFFFFFFu, kUnclassified = 0xFFFFFFFEu;

struct ShadingClusterSettings {
    int clusters = 1600;      // K (the paper: 1000-6000)
    float alpha = 0.3f;       // Eq. 2's weight of position, in 1 / scene size (the paper: 0.1-0.5)
    int iterations = 4;       // k-means iterations, at most
    float tolerance = 0.002f; // converged: an iteration moved at most this fraction of the pixels
    bool temporal = true;     // reuse the previous frame's clusters
    float errorSlack = 0.05f; // temporal: a point joins a previous cluster within 1 + this of its largest error
    std::uint32_t seed = 1;
    bool bruteForce = false; // tests: nearest centres by trying every one
    bool everyPixel = false; // no clustering: every shading point its own cluster and sample (Fig. 6)
};

class ShadingClusters {
public:
    // With temporal reuse and at most this many new clusters, a kept pixel's k-means assignment tries its
    // survivor and every new cluster instead of walking the tree of centres (kmeans_assign.comp).
    static constexpr std::uint32_t kShortcutNew = 128;

    explicit ShadingClusters(const ShadingClusterSettings& settings);

    // Clusters the frame's shading points. counters: the family's counters buffer.
    void cluster(const Frame& frame, float sceneSize, Buffer& counters, PassTimers& timers);
    // Forgets the previous frame's clusters (the next frame seeds from scratch).
    void restart() { havePrevious_ = false; }

    std::uint32_t count() const { return count_; }         // clusters in clusters()
    std::uint32_t seedsPlaced() const { return seeds_; }   // this frame's new seeds
    std::uint32_t survivors() const { return survivors_; } // clusters kept from the previous frame
    std::uint32_t nonEmpty() const { return nonEmpty_; }   // clusters with members (and samples)
    int iterationsRun() const { return iterationsRun_; }   // this frame's k-means iterations (until converged)
    const Buffer& clusters() const { return clusters_; }
    Buffer& clusters() { return clusters_; } // tests write sample irradiances through it
    const Buffer& clusterOfPixel() const { return clusterOfPixel_; }
    // Binds the clusters at SSBO_CLUSTER_CENTRES.
    void bind() const;
    // Builds the tree of the clusters' samples (useSamples) or centres at SSBO_POINT_TREE; the tree's
    // depth goes to `program`'s pointTreeDepth with bindPointTree.
    void buildPointTree(bool useSamples, Buffer& counters);
    // The last buildPointTree's work, added to the scope that ran it.
    void addPointTreeWork(PassTimers::Scope& t) const;
    void bindPointTree(Program& program) const;
    const Buffer& pointTree() const { return pointTree_; }
    int pointTreeDepth() const { return pointDepth_; }
    float alphaPerMetre() const { return alpha_; }

    std::vector<GpuCluster> download() const;
    std::vector<std::uint32_t> downloadClusterOfPixel() const;
    // The last seeding quadtree: level 0 (quadSize() x quadSize() pixels) first, each level's nodes row by
    // row, quadLevels() levels above the pixels.
    std::vector<GpuQuadNode> downloadQuadtree() const { return quad_.download<GpuQuadNode>(); }
    int quadSize() const { return quadSize_; }
    int quadLevels() const { return quadLevels_; }
    std::size_t bytes() const;

private:
    ShadingClusterSettings settings_;
    Program quadLeaves_, quadReduce_, quadError_, quadErrorGroup_, seedDistribute_, seedWrite_, pointKeys_,
        pointLeaves_, pointReduce_, assign_, segments_, update_, sample_, marks_, survivorsProgram_, survivorOfPixel_,
        perPixel_;
    GpuScan scan_;
    RadixSort sort_;
    Buffer quad_, seedsBuffer_, clusterOfPixel_, clusters_, spare_, keys_, values_, keysTmp_, valuesTmp_, pointTree_,
        marksBuffer_, survivorOfPixelBuffer_;
    int width_ = 0, height_ = 0, quadSize_ = 1, quadLevels_ = 0, pointDepth_ = 0;
    std::uint32_t count_ = 0, seeds_ = 0, survivors_ = 0, nonEmpty_ = 0;
    int iterationsRun_ = 0;
    float alpha_ = 0.0f;
    glm::vec3 lo_{0.0f}, extent_{1.0f};
    bool havePrevious_ = false;

    void allocate(int width, int height);
    // Each step adds its kernels' work to `t`, the "kmeans" scope.
    void buildQuadtree(bool onlyUnclassified, PassTimers::Scope& t);
    void placeSeeds(std::uint32_t first, std::uint32_t count, Buffer& counters, PassTimers::Scope& t);
    // countMoves: returns the pixels whose cluster changed (a read-back), else 0.
    std::uint32_t assign(bool onlyClassify, bool countMoves, Buffer& counters, PassTimers::Scope& t);
    void sortByCluster(Buffer& counters, PassTimers::Scope& t);
    void runSegments(PassTimers::Scope& t);
    void setCommon(Program& p) const;
};

} // namespace bounce::gl
