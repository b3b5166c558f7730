// Blue-noise surface points (core/surface_points.h): the areas they carry, the minimum distance the
// method guarantees (and white noise breaks), determinism, points on their triangles, counts per
// triangle proportional to area, and the hard cases (N = 1, N below the triangle count, a degenerate
// triangle, NaN input, scenes scaled by 1000 and 1/1000).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/sampling.h"
#include "core/surface_points.h"
#include "tests/alpha_mask_scene.h"

namespace bounce {
namespace {

using core::SurfacePoint;

// An axis-aligned cube of side `side` at the origin: six quads, twelve triangles, area 6 side^2.
core::Scene cube(float side)
{
    core::Scene s;
    s.materials.emplace_back();
    core::Mesh m;
    m.name = "cube";
    const auto quad = [&](glm::vec3 o, glm::vec3 u, glm::vec3 v) {
        const glm::vec3 n = glm::normalize(glm::cross(u, v));
        const auto base = std::uint32_t(m.positions.size());
        for (const glm::vec3& p : {o, o + u, o + u + v, o + v}) {
            m.positions.push_back(p * side);
            m.normals.push_back(n);
        }
        for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
    };
    quad({0, 0, 0}, {0, 1, 0}, {1, 0, 0});
    quad({0, 0, 1}, {1, 0, 0}, {0, 1, 0});
    quad({0, 0, 0}, {0, 0, 1}, {0, 1, 0});
    quad({1, 0, 0}, {0, 1, 0}, {0, 0, 1});
    quad({0, 0, 0}, {1, 0, 0}, {0, 0, 1});
    quad({0, 1, 0}, {0, 0, 1}, {1, 0, 0});
    s.meshes.push_back(m);
    return s;
}

core::Scene scaled(core::Scene s, float factor)
{
    for (core::Mesh& m : s.meshes)
        for (glm::vec3& p : m.positions) p *= factor;
    return s;
}

std::vector<glm::vec3> positionsOf(const core::Scene& scene, const std::vector<SurfacePoint>& points)
{
    std::vector<glm::vec3> out;
    for (const core::SurfaceSample& s : core::evaluateSurfacePoints(scene, points)) out.push_back(s.position);
    return out;
}

// Brute force over every pair (the independent, slow path), in double.
double minPairDistance(const std::vector<glm::vec3>& p)
{
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < p.size(); ++i)
        for (std::size_t j = i + 1; j < p.size(); ++j)
            best = std::min(best, glm::length(glm::dvec3(p[i]) - glm::dvec3(p[j])));
    return best;
}

// White noise over the same surfaces: triangles by area, uniform inside (the first step alone).
std::vector<glm::vec3> whiteNoise(const core::Scene& scene, std::size_t count, std::uint64_t seed)
{
    const core::DiscreteDistribution pick(core::triangleAreas(scene));
    core::Pcg32 rng(seed);
    std::vector<SurfacePoint> points;
    for (std::size_t i = 0; i < count; ++i) {
        float u = 0.0f;
        const auto t = std::uint32_t(pick.sample(rng.nextFloat(), &u));
        points.push_back({t, core::sampleUniformTriangle({u, rng.nextFloat()}), 0.0f});
    }
    return positionsOf(scene, points);
}

double bound(const core::SurfacePoints& sp)
{
    return core::kMinDistanceFactor * std::sqrt(sp.totalAreaM2 / double(sp.points.size()));
}

TEST(SurfacePoints, AreasSumToTheSurfaceArea)
{
    // A cube of side 2: 24 m^2 in closed form.
    const core::SurfacePoints c = core::sampleSurfacePoints(cube(2.0f), 1000, 1);
    EXPECT_NEAR(c.totalAreaM2, 24.0, 1e-9);
    double sum = 0.0;
    for (const SurfacePoint& p : c.points) sum += p.areaM2;
    EXPECT_NEAR(sum, 24.0, 24.0 * 1e-6);

    // The Cornell box: the sum of its triangles' areas.
    const core::Scene cornell = core::makeCornell("cornell-spot");
    double area = 0.0;
    for (double a : core::triangleAreas(cornell)) area += a;
    const core::SurfacePoints p = core::sampleSurfacePoints(cornell, 3000, 1);
    ASSERT_EQ(p.points.size(), 3000u);
    EXPECT_NEAR(p.totalAreaM2, area, area * 1e-12);
    sum = 0.0;
    for (const SurfacePoint& q : p.points) sum += q.areaM2;
    EXPECT_NEAR(sum, area, area * 1e-6);
}

// The guarantee: every pair at least r = 0.65 sqrt(A / N) apart (no restart on the Cornell box), checked
// pair by pair. White noise with the same count breaks it by far: its closest pair of N uniform
// points is near sqrt(A / (pi N^2)), i.e. ~0.01 of the bound at N = 3000.
TEST(SurfacePoints, MinimumDistanceIsThePoissonDiskRadius)
{
    const core::Scene cornell = core::makeCornell("cornell-spot");
    const core::SurfacePoints sp = core::sampleSurfacePoints(cornell, 3000, 7);
    EXPECT_EQ(sp.restarts, 0);
    EXPECT_DOUBLE_EQ(sp.minDistance, bound(sp));
    const double blue = minPairDistance(positionsOf(cornell, sp.points));
    const double white = minPairDistance(whiteNoise(cornell, 3000, 7));
    std::printf("[ measured ] closest pair: blue noise %.5g m, white noise %.5g m, bound %.5g m\n", blue, white,
                bound(sp));
    EXPECT_GE(blue, bound(sp) * (1.0 - 1e-5));
    EXPECT_LT(white, 0.2 * bound(sp));
}

TEST(SurfacePoints, SameSeedSamePointsOtherSeedOtherPoints)
{
    const core::Scene cornell = core::makeCornell("cornell-spot");
    const auto a = core::sampleSurfacePoints(cornell, 2000, 11).points;
    const auto b = core::sampleSurfacePoints(cornell, 2000, 11).points;
    const auto c = core::sampleSurfacePoints(cornell, 2000, 12).points;
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(a.size(), c.size());
    std::size_t sameAb = 0, sameAc = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        sameAb += a[i].triangle == b[i].triangle && a[i].barycentrics == b[i].barycentrics;
        sameAc += a[i].triangle == c[i].triangle && a[i].barycentrics == c[i].barycentrics;
    }
    EXPECT_EQ(sameAb, a.size());
    EXPECT_EQ(sameAc, 0u);
}

// Barycentrics inside the triangle, and the evaluated position lies on it: recovered independently
// by projecting onto the triangle's plane and solving for the barycentrics (in double).
TEST(SurfacePoints, PointsLieOnTheirTriangles)
{
    const core::Scene cornell = core::makeCornell("cornell-spot");
    const auto pts = core::sampleSurfacePoints(cornell, 2000, 3).points;
    const auto samples = core::evaluateSurfacePoints(cornell, pts);
    std::vector<std::array<glm::dvec3, 3>> tris;
    for (const core::Mesh& m : cornell.meshes)
        for (std::size_t i = 0; i < m.indices.size(); i += 3)
            tris.push_back({glm::dvec3(m.positions[m.indices[i]]), glm::dvec3(m.positions[m.indices[i + 1]]),
                            glm::dvec3(m.positions[m.indices[i + 2]])});
    for (std::size_t k = 0; k < pts.size(); ++k) {
        const glm::vec2 b = pts[k].barycentrics;
        ASSERT_TRUE(b.x >= 0.0f && b.y >= 0.0f && b.x + b.y <= 1.0f) << k;
        const auto& [p0, p1, p2] = tris.at(pts[k].triangle);
        const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
        const glm::dvec3 p(samples[k].position);
        EXPECT_LT(std::abs(glm::dot(p - p0, n)) / glm::length(n), 1e-6) << k << ": off the triangle's plane";
        // Barycentrics from sub-triangle areas: all three >= 0 (to rounding) means inside.
        const double a0 = glm::dot(glm::cross(p1 - p, p2 - p), n), a1 = glm::dot(glm::cross(p2 - p, p0 - p), n),
                     a2 = glm::dot(glm::cross(p0 - p, p1 - p), n), whole = glm::dot(n, n);
        EXPECT_GT(a0 / whole, -1e-5) << k;
        EXPECT_GT(a1 / whole, -1e-5) << k;
        EXPECT_GT(a2 / whole, -1e-5) << k;
        EXPECT_NEAR(a0 / whole, b.x, 1e-4) << k;
        EXPECT_NEAR(a1 / whole, b.y, 1e-4) << k;
        EXPECT_NEAR(glm::dot(glm::dvec3(samples[k].geometricNormal), n / glm::length(n)), 1.0, 1e-5);
        EXPECT_NEAR(glm::length(samples[k].normal), 1.0f, 1e-5f);
    }
}

// Counts per triangle against N a_i / A: Pearson's statistic over the triangles. White noise gives a
// chi-square with T - 1 degrees of freedom (mean T - 1); blue noise is more even than that, so the bound
// T - 1 + 4 sqrt(2 (T - 1)) (four standard deviations of white noise) is loose for a correct sampler,
// while a sampler that ignored area (one triangle chosen uniformly) gives thousands.
TEST(SurfacePoints, CountsPerTriangleFollowArea)
{
    const core::Scene cornell = core::makeCornell("cornell-spot");
    const std::size_t n = 20000;
    const core::SurfacePoints sp = core::sampleSurfacePoints(cornell, n, 5);
    const std::vector<double> areas = core::triangleAreas(cornell);
    std::vector<double> counts(areas.size(), 0.0);
    for (const SurfacePoint& p : sp.points) counts.at(p.triangle) += 1.0;
    double chi2 = 0.0;
    int dof = -1;
    for (std::size_t t = 0; t < areas.size(); ++t) {
        const double expected = double(n) * areas[t] / sp.totalAreaM2;
        ASSERT_GT(expected, 5.0) << "triangle " << t << " too small for Pearson's statistic";
        chi2 += (counts[t] - expected) * (counts[t] - expected) / expected;
        ++dof;
    }
    std::printf("[ measured ] Pearson chi^2 %.3g over %d degrees of freedom\n", chi2, dof);
    EXPECT_LT(chi2, dof + 4.0 * std::sqrt(2.0 * dof));
}

TEST(SurfacePoints, OnePoint)
{
    const core::Scene cornell = core::makeCornell("cornell-spot");
    const core::SurfacePoints sp = core::sampleSurfacePoints(cornell, 1, 1);
    ASSERT_EQ(sp.points.size(), 1u);
    EXPECT_NEAR(sp.points[0].areaM2, sp.totalAreaM2, sp.totalAreaM2 * 1e-6);
    EXPECT_TRUE(core::sampleSurfacePoints(cornell, 0, 1).points.empty());
}

// Fewer points than triangles: still exactly N, still r-separated with the radius the result states.
TEST(SurfacePoints, FewerPointsThanTriangles)
{
    const core::Scene cornell = core::makeCornell("cornell-spot");
    const std::size_t n = 5;
    ASSERT_GT(cornell.triangleCount(), n);
    const core::SurfacePoints sp = core::sampleSurfacePoints(cornell, n, 2);
    ASSERT_EQ(sp.points.size(), n);
    EXPECT_GT(sp.minDistance, 0.0);
    EXPECT_GE(minPairDistance(positionsOf(cornell, sp.points)), sp.minDistance * (1.0 - 1e-5));
}

// A zero-area triangle (three collinear vertices) between two good ones: no point on it, no area.
TEST(SurfacePoints, DegenerateTriangleGetsNoPoints)
{
    core::Scene s = cube(1.0f);
    core::Mesh& m = s.meshes[0];
    const auto base = std::uint32_t(m.positions.size());
    for (const glm::vec3& p : {glm::vec3(0, 0, 0), glm::vec3(0.5f, 0.5f, 0.5f), glm::vec3(1, 1, 1)}) {
        m.positions.push_back(p);
        m.normals.emplace_back(0, 1, 0);
    }
    m.indices.insert(m.indices.begin() + 6, {base, base + 1, base + 2}); // global triangle 2
    ASSERT_EQ(core::triangleAreas(s)[2], 0.0);
    const core::SurfacePoints sp = core::sampleSurfacePoints(s, 2000, 4);
    EXPECT_NEAR(sp.totalAreaM2, 6.0, 1e-9);
    ASSERT_EQ(sp.points.size(), 2000u);
    for (const SurfacePoint& p : sp.points) EXPECT_NE(p.triangle, 2u);
}

TEST(SurfacePoints, RefusesNaNAndOutOfRangeInput)
{
    core::Scene s = cube(1.0f);
    s.meshes[0].positions[3].y = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(core::sampleSurfacePoints(s, 10, 1), core::SurfacePointError);
    try {
        core::sampleSurfacePoints(s, 10, 1);
    } catch (const core::SurfacePointError& e) {
        EXPECT_NE(std::string(e.what()).find("cube"), std::string::npos) << e.what();
    }
    const core::Scene good = cube(1.0f);
    EXPECT_THROW(core::evaluateSurfacePoint(good, {12u, {0.3f, 0.3f}, 0.0f}), core::SurfacePointError);
    core::Scene empty;
    EXPECT_THROW(core::sampleSurfacePoints(empty, 10, 1), core::SurfacePointError);
}

// Mean distance to the nearest other point over r (brute force).
double meanNearestOverR(const std::vector<glm::vec3>& p, double r)
{
    double sum = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j < p.size(); ++j)
            if (j != i) best = std::min(best, glm::length(glm::dvec3(p[i]) - glm::dvec3(p[j])));
        sum += best;
    }
    return sum / double(p.size()) / r;
}

// The method is scale-free. Scaled by 1024 and 1/1024 every float operation scales exactly, so the very
// same (triangle, barycentrics) come out. Scaled by 1000 and 1/1000 the vertices round differently
// (~1e-7 relative) and a distance that ties with r may go the other way, which changes the dart
// throwing from there on: the layout is then the same in distribution (count, radius, guarantee,
// nearest-neighbour spacing, counts per triangle), not point for point.
TEST(SurfacePoints, HugeAndTinyScenesGiveTheSameLayout)
{
    const core::Scene cornell = core::makeCornell("cornell-spot");
    const std::size_t n = 2000;
    const core::SurfacePoints base = core::sampleSurfacePoints(cornell, n, 9);
    for (float factor : {1024.0f, 1.0f / 1024.0f}) {
        const core::SurfacePoints s = core::sampleSurfacePoints(scaled(cornell, factor), n, 9);
        ASSERT_EQ(s.points.size(), n) << factor;
        EXPECT_EQ(s.minDistance, base.minDistance * factor) << factor;
        for (std::size_t i = 0; i < n; ++i) {
            EXPECT_EQ(s.points[i].triangle, base.points[i].triangle) << factor << ", point " << i;
            EXPECT_EQ(s.points[i].barycentrics, base.points[i].barycentrics) << factor << ", point " << i;
        }
    }
    const double baseSpacing = meanNearestOverR(positionsOf(cornell, base.points), base.minDistance);
    for (float factor : {1000.0f, 0.001f}) {
        const core::Scene big = scaled(cornell, factor);
        const core::SurfacePoints s = core::sampleSurfacePoints(big, n, 9);
        ASSERT_EQ(s.points.size(), n) << factor;
        EXPECT_EQ(s.restarts, base.restarts) << factor;
        EXPECT_NEAR(s.minDistance / base.minDistance, factor, factor * 1e-5) << factor;
        EXPECT_NEAR(s.totalAreaM2 / base.totalAreaM2, double(factor) * factor, double(factor) * factor * 1e-5);
        const std::vector<glm::vec3> p = positionsOf(big, s.points);
        EXPECT_GE(minPairDistance(p), s.minDistance * (1.0 - 1e-5)) << factor;
        const double spacing = meanNearestOverR(p, s.minDistance);
        std::printf("[ measured ] x%g: mean nearest neighbour %.4f r (unscaled %.4f r)\n", factor, spacing,
                    baseSpacing);
        EXPECT_NEAR(spacing, baseSpacing, 0.02 * baseSpacing) << factor;
        const std::vector<double> areas = core::triangleAreas(big);
        std::vector<int> counts(areas.size(), 0), baseCounts(areas.size(), 0);
        for (const SurfacePoint& q : s.points) ++counts.at(q.triangle);
        for (const SurfacePoint& q : base.points) ++baseCounts.at(q.triangle);
        for (std::size_t t = 0; t < areas.size(); ++t) {
            const double expected = double(n) * areas[t] / s.totalAreaM2;
            EXPECT_NEAR(counts[t], baseCounts[t], 4.0 * std::sqrt(expected) + 2.0) << factor << ", triangle " << t;
        }
    }
}

// Points follow the geometry: move the scene and the same points evaluate to moved positions.
TEST(SurfacePoints, PointsFollowTheGeometry)
{
    const core::Scene a = cube(1.0f);
    core::Scene b = a;
    for (glm::vec3& p : b.meshes[0].positions) p += glm::vec3(3.0f, -1.0f, 2.0f);
    const auto pts = core::sampleSurfacePoints(a, 100, 1).points;
    const auto pa = positionsOf(a, pts), pb = positionsOf(b, pts);
    for (std::size_t i = 0; i < pts.size(); ++i)
        EXPECT_LT(glm::length(pb[i] - pa[i] - glm::vec3(3.0f, -1.0f, 2.0f)), 1e-5f) << i;
}

// Not part of the suite (timings are never asserted): how long a large cloud takes.
// Run with --gtest_also_run_disabled_tests --gtest_filter=SurfacePoints.DISABLED_Timing
TEST(SurfacePoints, DISABLED_Timing)
{
    const core::Scene cornell = core::makeCornell("cornell-spot");
    for (std::size_t n : {std::size_t(1) << 18, std::size_t(1) << 20}) {
        const auto start = std::chrono::steady_clock::now();
        const core::SurfacePoints sp = core::sampleSurfacePoints(cornell, n, 1);
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("[ measured ] %zu points in %.2f s (%d restarts)\n", sp.points.size(), s, sp.restarts);
    }
}

// Alpha masks: no point lands in a hole, and the area the points share is the opaque part's. A 2 m floor
// under the masked quad of tests/alpha_mask_scene.h, whose left half (x < 0) is a hole: 4.5 m^2 opaque of
// 5. Taken as opaque, 208 of the 2000 points lay in the hole and the area was 5.
TEST(SurfacePoints, PointsLeaveTheHolesOfAlphaMasks)
{
    core::Scene scene;
    core::Material white;
    scene.materials.push_back(white);
    core::Mesh floor;
    floor.positions = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
    floor.normals.assign(4, glm::vec3(0, 1, 0));
    floor.indices = {0, 1, 2, 0, 2, 3};
    scene.meshes.push_back(floor);
    testing::addMaskedQuad(scene);
    const core::SurfacePoints sp = core::sampleSurfacePoints(scene, 2000, 7);
    ASSERT_EQ(sp.points.size(), 2000u);
    int hole = 0, opaque = 0;
    for (const core::SurfaceSample& s : core::evaluateSurfacePoints(scene, sp.points)) {
        if (std::abs(s.position.y - testing::kMaskQuadHeight) > 1e-4f) continue;
        hole += s.position.x < -1e-3f;
        opaque += s.position.x > 1e-3f;
    }
    std::printf("[ measured ] %d points in the hole, %d on the opaque half, area %.4f m^2\n", hole, opaque,
                sp.totalAreaM2);
    EXPECT_EQ(hole, 0);
    EXPECT_GT(opaque, 150); // 2000 x 0.5 / 4.5 = 222 expected
    EXPECT_NEAR(sp.totalAreaM2, 4.5, 0.05);
}

} // namespace
} // namespace bounce
