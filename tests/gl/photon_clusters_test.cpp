// Shading clusters (gl/technique/photon/shading_clusters.h, section 3.2) against their invariants and a
// CPU reference: exactly K seeds (or every shading point when there are fewer), every shading point in
// exactly one cluster and no background pixel in any, member counts that add up, the tree of centres
// giving exactly the brute force's clusters, a CPU nearest-centre search by Eq. 2 agreeing with the GPU's,
// samples that are their cluster's member nearest its centre, the same clusters from the same input, and
// the hard cases: empty clusters, a cluster whose normals cancel, a viewport smaller than K.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "gl/frame/frame.h"
#include "gl/technique/photon/photon_tracer.h"
#include "gl/technique/photon/shading_clusters.h"
#include "tests/gl/gl_test_fixture.h"
#include "tests/gl/photon_test_scenes.h"

namespace bounce {
namespace {

struct Clustered {
    std::vector<gl::GpuCluster> clusters;
    std::vector<std::uint32_t> ofPixel;
    std::vector<glm::vec4> position, normal;
    std::uint32_t seeds = 0, nonEmpty = 0;
    int iterations = 0;
    float alpha = 0.0f;
};

// `frames` clusterings of the scene's G-buffer; with `move`, the camera moves by it after the first.
Clustered clusterScene(const core::Scene& scene, int w, int h, const gl::ShadingClusterSettings& s, int frames = 1,
                       glm::vec3 move = glm::vec3(0.0f))
{
    gl::Frame frame(scene, photontest::smallFrame(w, h));
    gl::PassTimers timers;
    frame.beginFrame();
    frame.renderGBuffer(timers);
    gl::Buffer counters("photon.counters", gl::kCounterSlots * 4);
    gl::ShadingClusters clusters(s);
    const float size = glm::length(scene.bounds().extent());
    for (int i = 0; i < frames; ++i) {
        if (i == 1 && move != glm::vec3(0.0f)) {
            core::Camera camera = scene.camera;
            camera.position += move;
            frame.setCamera(camera);
            frame.beginFrame();
            frame.renderGBuffer(timers);
        }
        clusters.cluster(frame, size, counters, timers);
    }
    Clustered c;
    c.clusters = clusters.download();
    c.ofPixel = clusters.downloadClusterOfPixel();
    c.seeds = clusters.seedsPlaced();
    c.nonEmpty = clusters.nonEmpty();
    c.iterations = clusters.iterationsRun();
    c.alpha = clusters.alphaPerMetre();
    const std::vector<float> p = frame.readPositions(), n = frame.readNormals();
    for (std::size_t i = 0; i < p.size() / 4; ++i) {
        c.position.push_back({p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3]});
        c.normal.push_back({n[4 * i], n[4 * i + 1], n[4 * i + 2], n[4 * i + 3]});
    }
    return c;
}

float error(const Clustered& c, std::size_t pixel, const gl::GpuCluster& k)
{
    const glm::vec3 x(c.position[pixel]), n(c.normal[pixel]);
    // Eq. 2's normal term as the chord |n - n_k| (equal to sqrt(2 - 2 n . n_k) for unit normals), as
    // shading_clusters.glsl computes it: the square root's form magnifies an ulp of the dot product.
    const glm::vec3 nk(k.normal);
    const float normalTerm =
        glm::dot(nk, nk) > 0.5f ? glm::length(n - nk) : std::sqrt(std::max(0.0f, 2.0f - 2.0f * glm::dot(n, nk)));
    return c.alpha * glm::length(x - glm::vec3(k.centre)) + normalTerm;
}

std::size_t validPixels(const Clustered& c)
{
    return std::size_t(
        std::count_if(c.position.begin(), c.position.end(), [](const glm::vec4& p) { return p.w != 0.0f; }));
}

// Every shading point in exactly one cluster, none for the background; members add up.
void expectPartition(const Clustered& c)
{
    std::map<std::uint32_t, float> members;
    int wrong = 0;
    for (std::size_t i = 0; i < c.ofPixel.size(); ++i) {
        const bool valid = c.position[i].w != 0.0f;
        if (valid) {
            wrong += c.ofPixel[i] >= c.clusters.size();
            members[c.ofPixel[i]] += 1.0f;
        } else {
            wrong += c.ofPixel[i] != gl::kNoCluster;
        }
    }
    EXPECT_EQ(wrong, 0) << "pixels in no cluster, in one out of range, or background pixels in one";
    int mismatched = 0, sampleless = 0;
    for (std::uint32_t k = 0; k < c.clusters.size(); ++k) {
        mismatched += members.count(k) ? members[k] != c.clusters[k].centre.w : c.clusters[k].centre.w != 0.0f;
        sampleless += (c.clusters[k].centre.w > 0.0f) != (c.clusters[k].sample.w >= 0.0f);
    }
    EXPECT_EQ(mismatched, 0) << "clusters whose member count is not the number of pixels in them";
    EXPECT_EQ(sampleless, 0) << "clusters with members and no sample, or a sample and no members";
}

class PhotonClustersTest : public GlTest {};

TEST_F(PhotonClustersTest, ExactlyKSeedsAndAPartition)
{
    gl::ShadingClusterSettings s;
    s.clusters = 150;
    const Clustered c = clusterScene(core::makeCornell("cornell-spot"), 64, 48, s);
    std::printf("[ measured ] %u seeds, %zu clusters, %u with members, %zu shading points\n", c.seeds,
                c.clusters.size(), c.nonEmpty, validPixels(c));
    EXPECT_EQ(c.seeds, 150u);
    expectPartition(c);
}

// The seeding quadtree's eps_q (section 3.2: Eq. 2's error of a node's members to their mean, summed) against
// a CPU sum in double over the read-back G-buffer, node by node at every level, on a viewport that is not a
// power of two (nodes cut by its edges) and large enough that the top levels' nodes (more than 16 pixels
// a side) are summed by a work group each and the lower ones by one invocation each. The means come from
// the GPU's summed positions and normals, checked first against the CPU's sums.
TEST_F(PhotonClustersTest, QuadtreeErrorsAreEq2SummedOverEachNode)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    constexpr int w = 150, h = 70;
    photontest::ClusteredFrame c(scene, w, h, 64);
    gl::Frame& frame = c.frame;
    const gl::ShadingClusters& clusters = c.clusters;
    const std::vector<gl::GpuQuadNode> nodes = clusters.downloadQuadtree();
    const int size = clusters.quadSize(), levels = clusters.quadLevels();
    ASSERT_EQ(size, 256);
    const std::vector<float> p = frame.readPositions(), n = frame.readNormals();
    const double alpha = clusters.alphaPerMetre();

    std::size_t offset = 0;
    int compared = 0, wrongSums = 0, wrongErrors = 0;
    double largest = 0.0;
    for (int level = 0; level <= levels; ++level) {
        const int side = size >> level, span = 1 << level;
        for (int qy = 0; qy < side; ++qy)
            for (int qx = 0; qx < side; ++qx) {
                const gl::GpuQuadNode& node = nodes.at(offset + std::size_t(qy) * side + qx);
                glm::dvec3 sumP(0.0), sumN(0.0);
                int members = 0;
                for (int y = qy * span; y < std::min((qy + 1) * span, h); ++y)
                    for (int x = qx * span; x < std::min((qx + 1) * span, w); ++x) {
                        const std::size_t i = (std::size_t(y) * w + x) * 4;
                        if (p[i + 3] == 0.0f) continue;
                        sumP += glm::dvec3(p[i], p[i + 1], p[i + 2]);
                        sumN += glm::dvec3(n[i], n[i + 1], n[i + 2]);
                        ++members;
                    }
                wrongSums += node.position.w != float(members) ||
                             glm::length(glm::dvec3(node.position) - sumP) > 1e-4 * (1.0 + glm::length(sumP));
                if (level == 0 || members < 2) continue;
                // The node's centre as shading_clusters.glsl takes it: the mean position and mean normal.
                const glm::dvec3 mean = glm::dvec3(node.position) / double(node.position.w);
                const glm::dvec3 sn(node.normal); // meanNormal: cancelled normals give the zero normal
                const glm::dvec3 nk = glm::length(sn) > 1e-3 * double(members) ? glm::normalize(sn) : glm::dvec3(0.0);
                double eps = 0.0;
                for (int y = qy * span; y < std::min((qy + 1) * span, h); ++y)
                    for (int x = qx * span; x < std::min((qx + 1) * span, w); ++x) {
                        const std::size_t i = (std::size_t(y) * w + x) * 4;
                        if (p[i + 3] == 0.0f) continue;
                        const glm::dvec3 xi(p[i], p[i + 1], p[i + 2]), ni(n[i], n[i + 1], n[i + 2]);
                        const double normalTerm = glm::dot(nk, nk) > 0.5
                                                      ? glm::length(ni - nk)
                                                      : std::sqrt(std::max(0.0, 2.0 - 2.0 * glm::dot(ni, nk)));
                        eps += alpha * glm::length(xi - mean) + normalTerm;
                    }
                const double err = std::abs(double(node.normal.w) - eps) / std::max(eps, 1e-3);
                largest = std::max(largest, err);
                wrongErrors += err > 1e-3;
                ++compared;
            }
        offset += std::size_t(side) * side;
    }
    std::printf("[ measured ] %d nodes' eps_q against the CPU: largest relative difference %.3g\n", compared, largest);
    EXPECT_EQ(wrongSums, 0) << "nodes whose members or summed positions differ from the CPU's";
    EXPECT_EQ(wrongErrors, 0) << "nodes whose eps_q is off the CPU's sum by more than 1e-3";
    EXPECT_GT(compared, 1000);
}

// Fewer shading points than K (a 3 x 5 viewport): one seed per point, every cluster has its point.
TEST_F(PhotonClustersTest, FewerPointsThanKGiveOneSeedEach)
{
    gl::ShadingClusterSettings s;
    s.clusters = 100;
    const Clustered c = clusterScene(core::makeCornell("cornell-spot"), 3, 5, s);
    EXPECT_EQ(c.seeds, std::uint32_t(validPixels(c)));
    expectPartition(c);
}

// The tree of centres prunes by alpha |x - box|, a lower bound of Eq. 2: the clusters are exactly those
// of the brute-force search (the same centres at every iteration), bit for bit.
TEST_F(PhotonClustersTest, TreeSearchAgreesWithBruteForce)
{
    const core::Scene scene = core::makeCornell("cornell-area");
    gl::ShadingClusterSettings s;
    s.clusters = 200;
    s.iterations = 3;
    const Clustered tree = clusterScene(scene, 64, 64, s);
    s.bruteForce = true;
    const Clustered brute = clusterScene(scene, 64, 64, s);
    EXPECT_EQ(tree.ofPixel, brute.ofPixel);
    ASSERT_EQ(tree.clusters.size(), brute.clusters.size());
    EXPECT_EQ(std::memcmp(tree.clusters.data(), brute.clusters.data(), tree.clusters.size() * sizeof(gl::GpuCluster)),
              0);
}

// Temporal reuse's shortcut (kmeans_assign.comp): in the frame after the camera moved a little, every pixel
// the classification kept tries only its survivor and the new clusters, which the pixels the move uncovered
// seeded. Its clusters must be the brute force's, bit for bit.
TEST_F(PhotonClustersTest, SurvivorShortcutAgreesWithBruteForce)
{
    const core::Scene scene = core::makeCornell("cornell-area");
    gl::ShadingClusterSettings s;
    s.clusters = 200;
    s.iterations = 3;
    const glm::vec3 move(0.02f, 0.01f, 0.0f);
    const Clustered tree = clusterScene(scene, 64, 64, s, 2, move);
    s.bruteForce = true;
    const Clustered brute = clusterScene(scene, 64, 64, s, 2, move);
    std::printf("[ measured ] second frame: %u new clusters of %zu\n", tree.seeds, tree.clusters.size());
    EXPECT_GT(tree.seeds, 0u) << "no new cluster: the shortcut's new clusters go untested";
    EXPECT_LE(tree.seeds, gl::ShadingClusters::kShortcutNew) << "too many new clusters: the shortcut is not taken";
    EXPECT_EQ(tree.ofPixel, brute.ofPixel);
    ASSERT_EQ(tree.clusters.size(), brute.clusters.size());
    EXPECT_EQ(std::memcmp(tree.clusters.data(), brute.clusters.data(), tree.clusters.size() * sizeof(gl::GpuCluster)),
              0);
    expectPartition(tree);
}

// A CPU reference of the classification and sample steps: every point's cluster is one of least Eq. 2
// error to the final centres (computed here in float), and every sample is its cluster's member of least error.
TEST_F(PhotonClustersTest, CpuNearestCentresAndSamplesAgree)
{
    gl::ShadingClusterSettings s;
    s.clusters = 120;
    const Clustered c = clusterScene(core::makeCornell("cornell-glossy"), 48, 48, s);
    int worse = 0, badSample = 0;
    std::map<std::uint32_t, std::pair<float, std::size_t>> nearest; // cluster -> least member error, pixel
    for (std::size_t i = 0; i < c.ofPixel.size(); ++i) {
        if (c.position[i].w == 0.0f) continue;
        float best = 3e38f;
        for (const gl::GpuCluster& k : c.clusters)
            if (k.centre.w > 0.0f) best = std::min(best, error(c, i, k));
        const float mine = error(c, i, c.clusters[c.ofPixel[i]]);
        worse += mine > best + 1e-5f * (1.0f + best);
        auto& n = nearest.try_emplace(c.ofPixel[i], 3e38f, 0).first->second;
        if (mine < n.first) n = {mine, i};
    }
    for (const auto& [k, n] : nearest) badSample += std::size_t(c.clusters[k].sample.w) != n.second;
    EXPECT_EQ(worse, 0) << "points whose cluster is not a nearest centre";
    EXPECT_EQ(badSample, 0) << "samples that are not their cluster's nearest member";
}

// k-means stops "when the clustering converges" (section 3.2): with tolerance 0, an iteration that moves no
// pixel. What it stops at must then be a fixed point of k-means, checked on the CPU: every cluster's
// centre its members' mean position and normal (and, by CpuNearestCentresAndSamplesAgree's check, every
// point in a nearest cluster). Stopping on the seeding iteration (whose moves are counted against another
// clustering) or on a count that misses moves leaves centres that are not their members' means.
TEST_F(PhotonClustersTest, KMeansStopsAtAFixedPointWhenNoPixelMoves)
{
    gl::ShadingClusterSettings s;
    s.clusters = 90;
    s.iterations = 64;
    s.tolerance = 0.0f;
    s.temporal = false;
    const Clustered c = clusterScene(core::makeCornell("cornell-spot"), 40, 40, s);
    std::printf("[ measured ] converged after %d iterations\n", c.iterations);
    EXPECT_LT(c.iterations, s.iterations) << "k-means never converged: the moves are not counted";
    EXPECT_GE(c.iterations, 2);
    std::map<std::uint32_t, std::pair<glm::dvec3, glm::dvec3>> sums;
    for (std::size_t i = 0; i < c.ofPixel.size(); ++i) {
        if (c.position[i].w == 0.0f) continue;
        auto& [x, n] = sums[c.ofPixel[i]];
        x += glm::dvec3(c.position[i]);
        n += glm::dvec3(c.normal[i]);
    }
    int offCentre = 0;
    for (const auto& [k, sum] : sums) {
        const gl::GpuCluster& cluster = c.clusters[k];
        const glm::dvec3 mean = sum.first / double(cluster.centre.w), normal = glm::normalize(sum.second);
        offCentre += glm::length(mean - glm::dvec3(cluster.centre)) > 1e-4 ||
                     glm::length(normal - glm::dvec3(cluster.normal)) > 1e-4;
    }
    EXPECT_EQ(offCentre, 0) << "clusters whose centre is not their members' mean: k-means stopped before converging";
    expectPartition(c);
}

TEST_F(PhotonClustersTest, SameInputGivesTheSameClusters)
{
    gl::ShadingClusterSettings s;
    s.clusters = 100;
    const core::Scene scene = core::makeCornell("cornell-point");
    const Clustered a = clusterScene(scene, 40, 40, s), b = clusterScene(scene, 40, 40, s);
    EXPECT_EQ(a.ofPixel, b.ofPixel);
    ASSERT_EQ(a.clusters.size(), b.clusters.size());
    EXPECT_EQ(std::memcmp(a.clusters.data(), b.clusters.data(), a.clusters.size() * sizeof(gl::GpuCluster)), 0);
}

// Temporal reuse with an unchanged view: every cluster takes its points again, none is new; the
// partition holds after reuse.
TEST_F(PhotonClustersTest, TemporalReuseKeepsTheClustersOfAStillView)
{
    gl::ShadingClusterSettings s;
    s.clusters = 100;
    const Clustered once = clusterScene(core::makeCornell("cornell-spot"), 40, 40, s, 1);
    const Clustered twice = clusterScene(core::makeCornell("cornell-spot"), 40, 40, s, 2);
    std::printf("[ measured ] second frame: %zu clusters, %u new seeds\n", twice.clusters.size(), twice.seeds);
    EXPECT_EQ(twice.clusters.size(), once.nonEmpty + twice.seeds);
    EXPECT_LE(twice.seeds, 5u);
    expectPartition(twice);
}

// Hard case: many seeds over few distinct points (alpha = 0: a wall's points all coincide): clusters that end empty have no
// sample, no NaN, and drop out; the partition holds.
TEST_F(PhotonClustersTest, EmptyClustersHaveNoSample)
{
    gl::ShadingClusterSettings s;
    s.clusters = 60;
    s.alpha = 0.0f; // Eq. 2 by normals alone: every wall is one point, its lowest cluster takes it whole
    const Clustered c = clusterScene(core::makeCornell("cornell-spot"), 32, 32, s);
    std::printf("[ measured ] %zu clusters, %u with members\n", c.clusters.size(), c.nonEmpty);
    EXPECT_LT(c.nonEmpty, c.clusters.size()) << "the case needs empty clusters";
    expectPartition(c);
    for (const gl::GpuCluster& k : c.clusters)
        for (int i = 0; i < 3; ++i) EXPECT_TRUE(std::isfinite(k.centre[i]) && std::isfinite(k.normal[i]));
}

// Hard case: a cluster whose members face opposite ways (floor and ceiling seen in equal parts, K = 1):
// the summed normal cancels; the centre keeps a unit normal and the sample is found.
TEST_F(PhotonClustersTest, OppositeNormalsKeepAUnitNormal)
{
    core::Scene s = photontest::closedBox(0.5f);
    s.meshes[0].indices.resize(12); // the floor and the ceiling only
    s.camera.position = {0.05f, 0.5f, 0.5f};
    s.camera.forward = {1.0f, 0.0f, 0.0f};
    s.camera.up = {0.0f, 0.0f, 1.0f}; // floor on one side of the image, ceiling on the other
    s.camera.yfovRad = 3.0f;
    gl::ShadingClusterSettings settings;
    settings.clusters = 1;
    settings.alpha = 0.0f;
    const Clustered c = clusterScene(s, 15, 16, settings);
    glm::vec3 sum(0.0f);
    for (std::size_t i = 0; i < c.normal.size(); ++i)
        if (c.position[i].w != 0.0f) sum += glm::vec3(c.normal[i]);
    std::printf("[ measured ] summed normal (%g, %g, %g) over %zu points\n", sum.x, sum.y, sum.z, validPixels(c));
    ASSERT_EQ(c.clusters.size(), 1u);
    const glm::vec3 n(c.clusters[0].normal);
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f);
    EXPECT_GE(c.clusters[0].sample.w, 0.0f);
    expectPartition(c);
}

// alpha is per scene size: the scene at 1000 times the scale gives the same clusters up to rounding,
// which k-means amplifies (measured: 65% of the shading points keep their very sample pixel). What must
// not change is the clusters' shape: the mean position term |x - x_k| / scene size and the mean normal
// term sqrt(2 - 2 n . n_k) of the shading points to their centres, each within 5%. An alpha in absolute
// units would weigh position 1000 times more in the large scene.
TEST_F(PhotonClustersTest, AlphaIsPerSceneSize)
{
    const core::Scene scene = core::makeCornell("cornell-area");
    const core::Scene big = photontest::scaledScene(scene, 1000.0f);
    gl::ShadingClusterSettings s;
    s.clusters = 150;
    s.temporal = false;
    const Clustered a = clusterScene(scene, 48, 48, s), b = clusterScene(big, 48, 48, s);
    const auto terms = [](const Clustered& c, float size) {
        double position = 0.0, normal = 0.0;
        int n = 0;
        for (std::size_t i = 0; i < c.ofPixel.size(); ++i) {
            if (c.position[i].w == 0.0f) continue;
            const gl::GpuCluster& k = c.clusters[c.ofPixel[i]];
            position += glm::length(glm::vec3(c.position[i]) - glm::vec3(k.centre)) / size;
            normal += std::sqrt(std::max(0.0f, 2.0f - 2.0f * glm::dot(glm::vec3(c.normal[i]), glm::vec3(k.normal))));
            ++n;
        }
        return glm::dvec2(position, normal) / double(n);
    };
    const float size = glm::length(scene.bounds().extent());
    const glm::dvec2 ta = terms(a, size), tb = terms(b, 1000.0f * size);
    std::printf("[ measured ] position term %.5f vs %.5f at 1000 x, normal term %.5f vs %.5f\n", ta.x, tb.x, ta.y,
                tb.y);
    EXPECT_NEAR(tb.x, ta.x, 0.05 * ta.x);
    EXPECT_NEAR(tb.y, ta.y, 0.05 * ta.y + 1e-4);
}

} // namespace
} // namespace bounce
