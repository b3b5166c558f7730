// The BVH (core/bvh.h) against brute force over every triangle with the same watertight test, and its
// structure: every triangle in exactly one leaf of each copy, boxes that contain their children, miss
// links that visit every node once; hard cases: degenerate, NaN and Inf triangles, an empty scene, rays
// through the edges and vertices of a closed mesh.
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "core/bvh.h"
#include "core/cornell.h"
#include "core/teapot.h"

namespace bounce::core {
namespace {

struct Ray {
    glm::vec3 o, d;
    float tMin, tMax;
};

// The closest hit over every hittable triangle with the BVH's own triangle test.
bool bruteForce(const Scene& scene, const Ray& r, RayHit& hit)
{
    const WatertightRay ray(r.o, r.d);
    float best = r.tMax;
    bool found = false;
    std::uint32_t global = 0;
    for (const Mesh& m : scene.meshes)
        for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3, ++global) {
            const glm::vec3 p0 = m.positions[m.indices[i]], p1 = m.positions[m.indices[i + 1]],
                            p2 = m.positions[m.indices[i + 2]];
            if (!Bvh::hittable(p0, p1, p2)) continue;
            float t, b1, b2;
            if (!intersectTriangle(ray, p0, p1, p2, r.tMin, best, t, b1, b2)) continue;
            best = t;
            hit = {global, t, b1, b2};
            found = true;
        }
    return found;
}

void triangleOf(const Scene& scene, std::uint32_t global, glm::vec3 p[3])
{
    for (const Mesh& m : scene.meshes) {
        const std::uint32_t n = std::uint32_t(m.indices.size() / 3);
        if (global < n) {
            for (int k = 0; k < 3; ++k) p[k] = m.positions[m.indices[3 * global + k]];
            return;
        }
        global -= n;
    }
    FAIL() << "no triangle " << global;
}

std::vector<Ray> randomRays(const Scene& scene, int count, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    // Points on triangles: vertices, edge points and interiors, so that many rays graze edges and vertices.
    std::vector<glm::vec3> targets;
    Bounds b; // of the hittable triangles (a NaN or Inf vertex would make it useless)
    for (const Mesh& m : scene.meshes)
        for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
            const glm::vec3 p0 = m.positions[m.indices[i]], p1 = m.positions[m.indices[i + 1]],
                            p2 = m.positions[m.indices[i + 2]];
            if (!Bvh::hittable(p0, p1, p2)) continue;
            for (const glm::vec3& p : {p0, p1, p2}) b.extend(p);
            targets.push_back(p0);
            targets.push_back(0.5f * (p1 + p2));
            targets.push_back((p0 + p1 + p2) / 3.0f);
        }
    const glm::vec3 lo = b.lo - 0.5f * b.extent(), hi = b.hi + 0.5f * b.extent();
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        const glm::vec3 o = lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng));
        glm::vec3 d;
        if (i % 3 == 0 || targets.empty()) {
            do d = glm::vec3(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1);
            while (glm::length(d) < 0.1f);
        } else {
            d = targets[std::size_t(u(rng) * float(targets.size())) % targets.size()] - o;
        }
        if (i % 17 == 0) d.y = 0.0f; // axis-parallel components: zero in the slab test
        if (glm::length(d) == 0.0f) d = glm::vec3(0, 0, 1);
        const float tMin = i % 5 == 0 ? 0.3f * u(rng) : 0.0f;
        const float tMax = i % 7 == 0 ? 2.0f * u(rng) : std::numeric_limits<float>::infinity();
        rays.push_back({o, d, tMin, tMax});
    }
    return rays;
}

// BVH and brute force agree on every ray: the same hit or miss, the same t to the bit, the same
// triangle or, on a tie (a ray through an edge or vertex shared by triangles at the same t), one the
// brute force also hits at that t.
void expectMatchesBruteForce(const Scene& scene, const std::vector<Ray>& rays)
{
    const Bvh bvh(scene);
    int hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Ray& r = rays[i];
        RayHit a, b;
        const bool hitBvh = bvh.closestHit(r.o, r.d, r.tMin, r.tMax, a);
        const bool hitBrute = bruteForce(scene, r, b);
        ASSERT_EQ(hitBvh, hitBrute) << scene.name << " ray " << i;
        ASSERT_EQ(bvh.anyHit(r.o, r.d, r.tMin, r.tMax), hitBrute) << scene.name << " ray " << i;
        if (!hitBvh) continue;
        ++hits;
        ASSERT_EQ(a.t, b.t) << scene.name << " ray " << i;
        if (a.triangle != b.triangle) {
            glm::vec3 p[3];
            triangleOf(scene, a.triangle, p);
            float t, b1, b2;
            ASSERT_TRUE(intersectTriangle(WatertightRay(r.o, r.d), p[0], p[1], p[2], r.tMin, r.tMax, t, b1, b2));
            ASSERT_EQ(t, b.t) << scene.name << " ray " << i << ": a different triangle at a different distance";
        } else {
            ASSERT_EQ(a.b1, b.b1);
            ASSERT_EQ(a.b2, b.b2);
        }
    }
    EXPECT_GT(hits, int(rays.size()) / 4) << scene.name << ": too few rays hit to say much";
}

TEST(Bvh, ClosestHitEqualsBruteForceOnCornellVariants)
{
    for (const std::string& name : builtinSceneNames()) {
        const Scene scene = makeCornell(name);
        expectMatchesBruteForce(scene, randomRays(scene, 3000, 11));
    }
}

TEST(Bvh, ClosestHitEqualsBruteForceOnTheTeapot)
{
    const Scene scene = makeTeapotScene();
    ASSERT_GT(scene.triangleCount(), 1000u);
    expectMatchesBruteForce(scene, randomRays(scene, 1500, 5));
}

// Structure, on every copy: walking with every box hit visits each node once in array order; every
// triangle lies in exactly one leaf; boxes contain their children and their triangles.
void expectWellFormed(const Scene& scene)
{
    const Bvh bvh(scene);
    const std::size_t n = bvh.nodeCount();
    const auto& nodes = bvh.nodes();
    const auto& tris = bvh.triangles();
    ASSERT_EQ(nodes.size(), n * Bvh::kDirections);
    ASSERT_EQ(tris.size() + bvh.skippedTriangles(), scene.triangleCount());
    std::set<std::uint32_t> indices;
    for (const BvhTriangle& t : tris) EXPECT_TRUE(indices.insert(t.index).second) << "triangle " << t.index << " twice";
    EXPECT_LE(bvh.depth(), Bvh::kMaxDepth);

    const auto contains = [](const BvhNode& outer, const glm::vec3& lo, const glm::vec3& hi) {
        return glm::all(glm::lessThanEqual(outer.lo, lo)) && glm::all(glm::greaterThanEqual(outer.hi, hi));
    };
    for (int d = 0; d < Bvh::kDirections; ++d) {
        const int base = int(d * n);
        std::vector<int> seen(tris.size(), 0);
        int node = base, visited = 0;
        while (node >= 0) {
            ASSERT_EQ(node, base + visited) << "copy " << d << ": the walk skips or repeats a node";
            ++visited;
            const BvhNode& nd = nodes[std::size_t(node)];
            if (nd.leaf < 0) {
                const BvhNode& left = nodes[std::size_t(node + 1)];
                ASSERT_GE(left.miss, 0);
                const BvhNode& right = nodes[std::size_t(left.miss)];
                EXPECT_TRUE(contains(nd, left.lo, left.hi)) << "copy " << d << " node " << node;
                EXPECT_TRUE(contains(nd, right.lo, right.hi)) << "copy " << d << " node " << node;
                EXPECT_EQ(right.miss, nd.miss) << "the second child ends where its parent ends";
                ++node;
            } else {
                const int first = nd.leaf >> 5, count = nd.leaf & 31;
                for (int i = first; i < first + count; ++i) {
                    ++seen[std::size_t(i)];
                    for (const glm::vec3& v : {tris[i].v0, tris[i].v1, tris[i].v2})
                        EXPECT_TRUE(contains(nd, v, v)) << "copy " << d << " leaf " << node;
                }
                node = nd.miss;
            }
        }
        EXPECT_EQ(visited, int(n)) << "copy " << d;
        for (std::size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], 1) << "copy " << d << " triangle slot " << i;
    }
}

TEST(Bvh, EveryTriangleInExactlyOneLeafAndBoundsContainChildren)
{
    expectWellFormed(makeCornell("cornell-slats"));
    expectWellFormed(makeTeapotScene());
}

Mesh meshOf(std::vector<glm::vec3> positions)
{
    Mesh m;
    m.positions = std::move(positions);
    m.normals.assign(m.positions.size(), glm::vec3(0, 0, 1));
    for (std::uint32_t i = 0; i < m.positions.size(); ++i) m.indices.push_back(i);
    return m;
}

TEST(Bvh, DegenerateNanAndInfTrianglesAreLeftOut)
{
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    Scene scene;
    scene.materials.emplace_back();
    // Triangle 0: good. 1: repeated vertex. 2: collinear. 3: NaN. 4: Inf. 5: good, behind 0.
    scene.meshes.push_back(meshOf({{-1, -1, 1},
                                   {1, -1, 1},
                                   {0, 1, 1},
                                   {0, 0, 2},
                                   {0, 0, 2},
                                   {1, 0, 2},
                                   {-1, 0, 0.5f},
                                   {0, 0, 0.5f},
                                   {1, 0, 0.5f},
                                   {nan, 0, 0.5f},
                                   {1, 0, 0.5f},
                                   {0, 1, 0.5f},
                                   {-inf, -1, 0.7f},
                                   {inf, -1, 0.7f},
                                   {0, inf, 0.7f},
                                   {-1, -1, 3},
                                   {1, -1, 3},
                                   {0, 1, 3}}));
    const Bvh bvh(scene);
    EXPECT_EQ(bvh.skippedTriangles(), 4u);
    EXPECT_EQ(bvh.triangles().size(), 2u);
    for (const BvhNode& n : bvh.nodes())
        for (int k = 0; k < 3; ++k) {
            EXPECT_TRUE(std::isfinite(n.lo[k]));
            EXPECT_TRUE(std::isfinite(n.hi[k]));
        }
    RayHit hit;
    ASSERT_TRUE(bvh.closestHit({0, 0, 0}, {0, 0, 1}, 0.0f, inf, hit));
    EXPECT_EQ(hit.triangle, 0u);
    EXPECT_FLOAT_EQ(hit.t, 1.0f);
    ASSERT_TRUE(bvh.closestHit({0, 0, 0}, {0, 0, 1}, 1.5f, inf, hit)); // past triangle 0
    EXPECT_EQ(hit.triangle, 5u) << "global indices count the triangles left out";
    EXPECT_FALSE(bvh.anyHit({0, 0, 0}, {0, 0, 1}, 0.0f, 0.999f)); // short of it
    EXPECT_FALSE(bvh.anyHit({0, 0, 0}, {0, 0, -1}, 0.0f, inf));
    expectMatchesBruteForce(scene, randomRays(scene, 500, 3));
}

TEST(Bvh, EmptySceneMissesEverything)
{
    Scene scene;
    const Bvh bvh(scene);
    EXPECT_EQ(bvh.nodeCount(), 1u);
    RayHit hit;
    EXPECT_FALSE(bvh.closestHit({0, 0, 0}, {0, 0, 1}, 0.0f, 1e30f, hit));
    EXPECT_FALSE(bvh.anyHit({0, 0, 0}, {1, 0, 0}, 0.0f, 1e30f));
}

// Rays from inside the teapot's body aimed exactly at a vertex, or at a point of an edge, where the
// surface crosses the ray as one sheet (every triangle around the target faces the ray the same way,
// not edge-on): whatever the rounding of the direction, the ray must hit one of those triangles, at the
// target or before it (watertightness). Open edges (rim, lid, spout) and silhouette folds are left out:
// a ray that passes them by a rounding error rightly goes on.
TEST(Bvh, RaysThroughSharedEdgesAndVerticesNeverSlipThrough)
{
    const Scene scene = makeTeapotScene();
    const Mesh& m = scene.meshes[0];
    const glm::vec3 inside = scene.bounds().centre(); // inside the pot's body
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> edgeFaces;
    std::vector<std::vector<std::size_t>> vertexFaces(m.positions.size());
    for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
        if (!Bvh::hittable(m.positions[m.indices[i]], m.positions[m.indices[i + 1]], m.positions[m.indices[i + 2]]))
            continue;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = m.indices[i + k], b = m.indices[i + (k + 1) % 3];
            edgeFaces[{std::min(a, b), std::max(a, b)}].push_back(i);
            vertexFaces[a].push_back(i);
        }
    }
    std::vector<bool> onBoundary(m.positions.size(), false);
    for (const auto& [edge, faces] : edgeFaces)
        if (faces.size() != 2) onBoundary[edge.first] = onBoundary[edge.second] = true;
    // Whether every face faces the ray the same way, none of them within ~3 degrees of edge-on.
    const auto oneSheet = [&](const std::vector<std::size_t>& faces, const glm::vec3& d) {
        int sign = 0;
        for (std::size_t i : faces) {
            const glm::vec3 p0 = m.positions[m.indices[i]], p1 = m.positions[m.indices[i + 1]],
                            p2 = m.positions[m.indices[i + 2]];
            const float c = glm::dot(glm::normalize(glm::cross(p1 - p0, p2 - p0)), glm::normalize(d));
            if (std::abs(c) < 0.05f) return false;
            const int s = c > 0.0f ? 1 : -1;
            if (sign != 0 && s != sign) return false;
            sign = s;
        }
        return true;
    };
    const Bvh bvh(scene);
    int tested = 0;
    const auto expectHit = [&](const glm::vec3& target, const char* what, std::uint32_t a, std::uint32_t b) {
        const glm::vec3 d = target - inside;
        RayHit hit;
        ASSERT_TRUE(bvh.closestHit(inside, d, 0.0f, 1e30f, hit)) << what << " " << a << "-" << b;
        ASSERT_TRUE(bvh.anyHit(inside, d, 0.0f, 1e30f));
        ASSERT_LE(hit.t, 1.0f + 1e-5f) << "passed its target: slipped through " << what << " " << a << "-" << b;
        ++tested;
    };
    for (const auto& [edge, faces] : edgeFaces) {
        if (faces.size() != 2) continue;
        const glm::vec3 p0 = m.positions[edge.first], p1 = m.positions[edge.second];
        for (const glm::vec3& target : {0.5f * (p0 + p1), 0.8f * p0 + 0.2f * p1})
            if (oneSheet(faces, target - inside)) expectHit(target, "edge", edge.first, edge.second);
    }
    for (std::uint32_t v = 0; v < m.positions.size(); ++v)
        if (!onBoundary[v] && !vertexFaces[v].empty() && oneSheet(vertexFaces[v], m.positions[v] - inside))
            expectHit(m.positions[v], "vertex", v, v);
    EXPECT_GT(tested, 8000);
}

} // namespace
} // namespace bounce::core
