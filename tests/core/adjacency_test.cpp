// Triangle adjacency (core/adjacency.h) for the edges pass of the moving frames' edge antialiasing: each
// triangle's six GL_TRIANGLES_ADJACENCY indices. Hard cases: vertices split at a seam (other indices, the same
// positions), a non-manifold edge that three triangles share, a degenerate triangle, a lone triangle, and
// every edge of a closed mesh (the teapot's body is not closed; a cube is).
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "core/adjacency.h"

namespace bounce::core {
namespace {

// Triangle t's slot after edge k: the far corner across the edge from corner k to corner k + 1.
std::uint32_t across(const std::vector<std::uint32_t>& adjacency, int t, int k)
{
    return adjacency[6 * t + 2 * k + 1];
}

TEST(Adjacency, TwoTrianglesOfAQuadSeeEachOtherAcrossTheDiagonal)
{
    const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 2, 3};
    const std::vector<std::uint32_t> a = triangleAdjacency(p, idx);
    ASSERT_EQ(a.size(), 12u);
    // Corners in the even slots, in the triangle's order.
    EXPECT_EQ(a[0], 0u);
    EXPECT_EQ(a[2], 1u);
    EXPECT_EQ(a[4], 2u);
    EXPECT_EQ(a[6], 0u);
    EXPECT_EQ(a[8], 2u);
    EXPECT_EQ(a[10], 3u);
    // The diagonal 2-0 of the first is 0-2 of the second: each sees the other's far corner.
    EXPECT_EQ(across(a, 0, 2), 3u);
    EXPECT_EQ(across(a, 1, 0), 1u);
    // The quad's outline: each triangle's own opposite corner.
    EXPECT_EQ(across(a, 0, 0), 2u);
    EXPECT_EQ(across(a, 0, 1), 0u);
    EXPECT_EQ(across(a, 1, 1), 0u);
    EXPECT_EQ(across(a, 1, 2), 2u);
}

TEST(Adjacency, SplitVerticesMeetByPosition)
{
    // The second triangle has its own copies of the diagonal's corners (a seam of normals or uvs).
    const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<std::uint32_t> a = triangleAdjacency(p, {0, 1, 2, 3, 4, 5});
    EXPECT_EQ(across(a, 0, 2), 5u);
    EXPECT_EQ(across(a, 1, 0), 1u);
}

TEST(Adjacency, NonManifoldEdgeIsABoundaryForEveryTriangleOnIt)
{
    // Three fins on the edge 0-1.
    const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, 0, 1}, {0.5f, -1, 0}};
    const std::vector<std::uint32_t> a = triangleAdjacency(p, {0, 1, 2, 1, 0, 3, 0, 1, 4});
    EXPECT_EQ(across(a, 0, 0), 2u);
    EXPECT_EQ(across(a, 1, 0), 3u);
    EXPECT_EQ(across(a, 2, 0), 4u);
}

TEST(Adjacency, DegenerateAndLoneTrianglesHaveNoNeighbours)
{
    const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<std::uint32_t> lone = triangleAdjacency(p, {0, 1, 2});
    const std::uint32_t opposite[3] = {2, 0, 1};
    for (int k = 0; k < 3; ++k) EXPECT_EQ(across(lone, 0, k), opposite[k]);
    // Corners 0 and 1 at one index: the edge 0-0 meets itself, the other two edges meet each other's reverse.
    const std::vector<std::uint32_t> degenerate = triangleAdjacency(p, {0, 0, 1});
    ASSERT_EQ(degenerate.size(), 6u);
    EXPECT_EQ(across(degenerate, 0, 0), 1u);
    EXPECT_TRUE(triangleAdjacency(p, {}).empty());
}

TEST(Adjacency, EveryEdgeOfAClosedCubeHasANeighbour)
{
    std::vector<glm::vec3> p;
    for (int i = 0; i < 8; ++i) p.push_back(glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
    const std::vector<std::uint32_t> idx = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                            2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
    const std::vector<std::uint32_t> a = triangleAdjacency(p, idx);
    for (int t = 0; t < 12; ++t)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t own = idx[3 * t + (k + 2) % 3];
            EXPECT_NE(across(a, t, k), own) << "triangle " << t << " edge " << k;
        }
}

} // namespace
} // namespace bounce::core
