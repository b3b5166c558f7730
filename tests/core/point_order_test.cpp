// The median-split order of the shared point cloud (core/point_order.h): a permutation; at every level each
// node's two halves lie on either side of a plane across the node's longest axis; the 512 clusters of
// point projection are equal; deterministic; non-power-of-two counts, single points and NaN positions.
#include <algorithm>
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/point_order.h"
#include "core/sampling.h"
#include "core/surface_points.h"

namespace bounce {
namespace {

std::vector<glm::vec3> randomPoints(std::size_t n, glm::vec3 scale)
{
    core::Pcg32 rng(42);
    std::vector<glm::vec3> p(n);
    for (glm::vec3& v : p) v = glm::vec3(rng.nextFloat(), rng.nextFloat(), rng.nextFloat()) * scale;
    return p;
}

// Checks the split of node [begin, end) at `level` and recurses.
void checkSplit(const std::vector<glm::vec3>& pos, const std::vector<std::uint32_t>& order, std::size_t begin,
                std::size_t end, int level, int levels)
{
    if (level >= levels || end - begin < 2) return;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (std::size_t i = begin; i < end; ++i) {
        lo = glm::min(lo, pos[order[i]]);
        hi = glm::max(hi, pos[order[i]]);
    }
    const glm::vec3 e = hi - lo;
    const int axis = (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
    const std::size_t mid = begin + (end - begin) / 2;
    float leftMax = -INFINITY, rightMin = INFINITY;
    for (std::size_t i = begin; i < mid; ++i) leftMax = std::max(leftMax, pos[order[i]][axis]);
    for (std::size_t i = mid; i < end; ++i) rightMin = std::min(rightMin, pos[order[i]][axis]);
    ASSERT_LE(leftMax, rightMin) << "level " << level << " node [" << begin << ", " << end << ") axis " << axis;
    checkSplit(pos, order, begin, mid, level + 1, levels);
    checkSplit(pos, order, mid, end, level + 1, levels);
}

TEST(PointOrder, IsAPermutationSplitAlongTheLongestAxisAtEveryLevel)
{
    for (std::size_t n : {1024u, 1000u, 3u, 1u}) {
        SCOPED_TRACE(n);
        const std::vector<glm::vec3> pos = randomPoints(n, {3.0f, 1.0f, 0.5f});
        const std::vector<std::uint32_t> order = core::medianSplitOrder(pos, 64);
        ASSERT_EQ(order.size(), n);
        std::set<std::uint32_t> seen(order.begin(), order.end());
        EXPECT_EQ(seen.size(), n);
        checkSplit(pos, order, 0, n, 0, 64);
    }
}

TEST(PointOrder, NineLevelsGive512EqualContiguousClusters)
{
    const std::vector<glm::vec3> pos = randomPoints(1 << 14, {1.0f, 2.0f, 1.0f});
    const std::vector<std::uint32_t> order = core::medianSplitOrder(pos, 9, core::SplitAxis::Cycle);
    // Cluster c is [c 32, (c + 1) 32): its bounding boxes along the split axes never overlap another's,
    // which is what checking the Cycle rule's splits means: the first split is along y (the longest).
    const std::size_t size = order.size() / 512;
    float leftMax = -INFINITY, rightMin = INFINITY;
    for (std::size_t i = 0; i < order.size() / 2; ++i) leftMax = std::max(leftMax, pos[order[i]].y);
    for (std::size_t i = order.size() / 2; i < order.size(); ++i) rightMin = std::min(rightMin, pos[order[i]].y);
    EXPECT_LE(leftMax, rightMin);
    // The second level of the cycle splits along z (after y), inside each half.
    for (int half = 0; half < 2; ++half) {
        const std::size_t b = half * order.size() / 2, m = b + order.size() / 4, e = b + order.size() / 2;
        float l = -INFINITY, r = INFINITY;
        for (std::size_t i = b; i < m; ++i) l = std::max(l, pos[order[i]].z);
        for (std::size_t i = m; i < e; ++i) r = std::min(r, pos[order[i]].z);
        EXPECT_LE(l, r);
    }
    EXPECT_EQ(size * 512, order.size());
}

TEST(PointOrder, DeterministicAndNanSafe)
{
    std::vector<glm::vec3> pos = randomPoints(257, {1.0f, 1.0f, 1.0f});
    pos[5] = glm::vec3(NAN, 0.0f, INFINITY);
    const auto a = core::medianSplitOrder(pos, 20), b = core::medianSplitOrder(pos, 20);
    EXPECT_EQ(a, b);
    std::set<std::uint32_t> seen(a.begin(), a.end());
    EXPECT_EQ(seen.size(), pos.size());
}

TEST(PointOrder, SurfacePointsOfTheCornellBoxKeepTheirAreas)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    const core::SurfacePoints sp = core::sampleSurfacePoints(scene, 1024, 3);
    const std::vector<core::SurfacePoint> ordered = core::orderSurfacePoints(scene, sp.points, 10);
    ASSERT_EQ(ordered.size(), sp.points.size());
    double area = 0.0;
    for (const core::SurfacePoint& p : ordered) area += p.areaM2;
    EXPECT_NEAR(area, sp.totalAreaM2, 1e-4 * sp.totalAreaM2);
    EXPECT_EQ(core::exactLog2(1024), 10);
    EXPECT_EQ(core::exactLog2(1000), -1);
    EXPECT_EQ(core::exactLog2(1), 0);
}

} // namespace
} // namespace bounce
