// GPU ray casting (glsl/common/raycast.glsl through gl/frame/ray_caster.h) against Embree (ref/), from a
// compute shader and from a fragment shader, on the Cornell variants and the Utah teapot: the same
// triangle and the same distance (1e-5 relative) on random rays from inside and outside the scene, rays
// through vertices and edges, grazing rays, rays that miss and rays cut short by tMin/tMax.
//
// Where the two disagree on the triangle at one distance, the ray runs through an edge or vertex that
// triangles share and each test picks a different one of them: accepted when the point Embree hit lies
// on the GPU's triangle. Where they disagree on the distance or on whether anything is hit, the nearer
// hit must lie on an edge of its triangle (Embree's test is not watertight; at open edges and
// silhouettes a ray rounded past the edge rightly misses) or at tMin/tMax. Tolerances: 1e-5 relative,
// widened by 1/cos for grazing rays, whose hit point along the plane no float test pins down better.
// Such rays are counted, printed and bounded.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/teapot.h"
#include "gl/frame/ray_caster.h"
#include "ref/embree_scene.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class RaycastTest : public GlTest {};

constexpr float kInf = std::numeric_limits<float>::infinity();

std::vector<gl::BatchRay> testRays(const core::Scene& scene, int count, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const core::Bounds b = scene.bounds();
    const glm::vec3 size = b.extent();
    struct Tri {
        glm::vec3 p[3];
    };
    std::vector<Tri> tris;
    for (const core::Mesh& m : scene.meshes)
        for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3)
            tris.push_back({{m.positions[m.indices[i]], m.positions[m.indices[i + 1]], m.positions[m.indices[i + 2]]}});
    const auto randomDir = [&] {
        for (;;) {
            const glm::vec3 v(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1);
            if (glm::length(v) > 0.1f && glm::length(v) <= 1.0f) return v;
        }
    };
    const auto anyTri = [&]() -> const Tri& { return tris[std::size_t(u(rng) * float(tris.size())) % tris.size()]; };
    std::vector<gl::BatchRay> rays;
    for (int i = 0; i < count; ++i) {
        gl::BatchRay r;
        r.tMin = 0.0f;
        r.tMax = kInf;
        const bool outside = i % 2 == 1;
        r.origin = outside ? b.centre() + (randomDir() * 2.0f) * glm::length(size)
                           : b.lo + size * glm::vec3(u(rng), u(rng), u(rng));
        switch (i % 6) {
        case 0: r.dir = randomDir(); break;                                // anywhere
        case 1: r.dir = anyTri().p[int(u(rng) * 3) % 3] - r.origin; break; // through a vertex
        case 2: {
            const Tri& t = anyTri();
            r.dir = glm::mix(t.p[0], t.p[1], u(rng)) - r.origin;
            break;
        }         // an edge
        case 3: { // grazing: from a point just off a triangle, almost along its plane
            const Tri& t = anyTri();
            const glm::vec3 n = glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]);
            if (glm::length(n) == 0.0f) {
                r.dir = randomDir();
                break;
            }
            const glm::vec3 nn = glm::normalize(n);
            const glm::vec3 inPlane = glm::normalize(t.p[1] - t.p[0]);
            r.origin = t.p[0] - inPlane * (0.1f * glm::length(size)) + nn * (1e-3f * u(rng));
            r.dir = inPlane - nn * (0.02f * u(rng));
            break;
        }
        case 4:
            r.dir = b.centre() - r.origin;
            if (outside) r.dir = -r.dir;
            break; // mostly misses from outside
        default: { // cut short: tMin/tMax around the scene
            r.dir = randomDir();
            r.tMin = 0.2f * u(rng) * glm::length(size);
            r.tMax = r.tMin + 0.5f * u(rng) * glm::length(size);
        }
        }
        if (glm::length(r.dir) == 0.0f) r.dir = randomDir();
        if (i % 23 == 0) r.dir.x = 0.0f; // zero components: the slab test's 0 * inf
        if (glm::length(r.dir) == 0.0f) r.dir = glm::vec3(0, 1, 0);
        rays.push_back(r);
    }
    return rays;
}

double segmentDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b)
{
    const glm::dvec3 ab = b - a;
    const double s = glm::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
    return glm::length(p - (a + s * ab));
}

// The distance from p to the triangle (p0, p1, p2), in double.
double pointTriangleDistance(const glm::dvec3& p, const glm::vec3& p0f, const glm::vec3& p1f, const glm::vec3& p2f)
{
    const glm::dvec3 p0(p0f), p1(p1f), p2(p2f);
    const glm::dvec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    const glm::dvec3 q = p - glm::dot(p - p0, n) * n; // p projected onto the plane
    const bool inside = glm::dot(glm::cross(p1 - q, p2 - q), n) >= 0 && glm::dot(glm::cross(p2 - q, p0 - q), n) >= 0 &&
                        glm::dot(glm::cross(p0 - q, p1 - q), n) >= 0;
    if (inside) return std::abs(glm::dot(p - p0, n));
    return std::min({segmentDistance(p, p0, p1), segmentDistance(p, p1, p2), segmentDistance(p, p2, p0)});
}

// Where (o, d) meets the plane of triangle (p0, p1, p2), in double: its t, how far that point lies
// outside the triangle (0 inside) and how far from the nearest edge. False when the ray is parallel.
struct Exact {
    double t = 0.0, outside = 0.0, edge = 0.0;
    double tolerance = 0.0; // how far float rounding may move the hit point in the plane
};
bool exactHit(const glm::vec3& of, const glm::vec3& df, const glm::vec3& p0f, const glm::vec3& p1f,
              const glm::vec3& p2f, Exact& x)
{
    const glm::dvec3 o(of), d(df), p0(p0f), p1(p1f), p2(p2f);
    const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
    const double dn = glm::dot(n, d);
    if (dn == 0.0 || glm::dot(n, n) == 0.0) return false;
    x.t = glm::dot(n, p0 - o) / dn;
    const glm::dvec3 p = o + x.t * d;
    const double b0 = glm::dot(glm::cross(p1 - p, p2 - p), n), b1 = glm::dot(glm::cross(p2 - p, p0 - p), n),
                 b2 = glm::dot(glm::cross(p0 - p, p1 - p), n);
    x.edge = std::min({segmentDistance(p, p0, p1), segmentDistance(p, p1, p2), segmentDistance(p, p2, p0)});
    x.outside = (b0 >= 0 && b1 >= 0 && b2 >= 0) ? 0.0 : x.edge;
    // Float rounding moves the ray and the vertices by ulps of the coordinates (1e-6 relative is some
    // ten ulps); along the plane that grows as 1 / cos of the angle between the ray and the normal.
    const double cosine = std::abs(dn) / (glm::length(n) * glm::length(d));
    x.tolerance = 1e-6 * std::max({1.0, glm::length(o), glm::length(p)}) / std::max(cosine, 1e-3);
    return true;
}

struct Tally {
    int rays = 0, hits = 0, sharedEdge = 0, embreeSlipped = 0, gpuSlipped = 0, anyDisagrees = 0;
};

void compareWithEmbree(const core::Scene& scene, const std::vector<gl::BatchRay>& rays,
                       const std::vector<gl::BatchResult>& gpu, Tally& tally)
{
    const ref::EmbreeScene embree(scene);
    std::uint64_t count = 0;
    ASSERT_EQ(gpu.size(), rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const gl::BatchRay& r = rays[i];
        const gl::BatchResult& g = gpu[i];
        ref::Hit e;
        const bool embreeHit = embree.intersect(r.origin, r.dir, r.tMin, r.tMax, e, count);
        const std::uint32_t et = embreeHit ? embree.globalTriangle(e.mesh, e.prim) : 0u;
        ++tally.rays;
        const auto where = [&] {
            char buf[256];
            std::snprintf(buf, sizeof buf, "%s ray %zu o=(%.9g,%.9g,%.9g) d=(%.9g,%.9g,%.9g) t=(%g,%g)",
                          scene.name.c_str(), i, r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z, r.tMin,
                          r.tMax);
            return std::string(buf);
        };
        // Where the ray meets a triangle, in double.
        // Whether the ray meets a triangle (to what rounding allows, Exact::tolerance), and where.
        const auto exact = [&](std::uint32_t tri, Exact& x) {
            glm::vec3 p0, p1, p2;
            std::uint32_t mesh;
            embree.triangle(tri, p0, p1, p2, mesh);
            return exactHit(r.origin, r.dir, p0, p1, p2, x) && x.outside <= x.tolerance;
        };
        if (g.closest) {
            ASSERT_LT(g.triangle, embree.triangleCount()) << where();
        }
        if (g.any != g.closest) {
            // Only through an edge: the two walks are separate code, and llvmpipe's fragment shaders were
            // seen to round one of them differently there (compute shaders agree on every ray).
            Exact x;
            ASSERT_TRUE(g.closest && exact(g.triangle, x) && x.edge <= 10.0 * x.tolerance)
                << where() << ": anyHit and closestHit disagree away from an edge";
            ++tally.anyDisagrees;
        }
        // 1e-5 relative, or for grazing rays what rounding the hit point along the plane gives.
        Exact ex;
        const bool embreeExact = embreeHit && exact(et, ex);
        const double tTolerance = 1e-5 * e.t + (embreeExact ? ex.tolerance / double(glm::length(r.dir)) : 0.0);
        const bool sameT = g.closest && embreeHit && std::abs(double(g.t) - e.t) <= tTolerance;
        // Two hit points that should be one: 1e-5 relative to the coordinates, more for grazing rays.
        const auto pointTolerance = [&](const glm::dvec3& p) {
            return std::max(1e-5 * std::max(1.0, glm::length(p)), embreeExact ? 10.0 * ex.tolerance : 0.0);
        };
        if (sameT && g.triangle == et) {
            ++tally.hits;
            // The same point of the same triangle, from the barycentrics of each.
            glm::vec3 p0, p1, p2;
            std::uint32_t mesh;
            embree.triangle(et, p0, p1, p2, mesh);
            const glm::vec3 pg = (1.0f - g.b1 - g.b2) * p0 + g.b1 * p1 + g.b2 * p2;
            const glm::vec3 pe = (1.0f - e.u - e.v) * p0 + e.u * p1 + e.v * p2;
            ASSERT_LE(glm::length(pg - pe), pointTolerance(pe)) << where();
            continue;
        }
        if (sameT) {
            ++tally.hits;
            // Two triangles at one distance: the ray runs through an edge or vertex they share. The
            // point Embree hit must lie on the GPU's triangle too (1e-5 relative to the coordinates).
            glm::vec3 p0, p1, p2;
            std::uint32_t mesh;
            embree.triangle(g.triangle, p0, p1, p2, mesh);
            const glm::dvec3 pe = glm::dvec3(r.origin) + double(e.t) * glm::dvec3(r.dir);
            const double dist = pointTriangleDistance(pe, p0, p1, p2);
            ASSERT_LE(dist, pointTolerance(pe))
                << where() << ": GPU triangle " << g.triangle << " is not where Embree hit " << et;
            ++tally.sharedEdge;
            continue;
        }
        if (!g.closest && !embreeHit) continue;
        // Different distances, or a hit for one only: the nearer hit must sit on an edge of its triangle
        // (the other test let the ray through that edge) or at tMin/tMax.
        const bool gpuNearer = g.closest && (!embreeHit || g.t < e.t);
        Exact x;
        ASSERT_TRUE(exact(gpuNearer ? g.triangle : et, x))
            << where() << ": the nearer hit (" << (gpuNearer ? "GPU" : "Embree") << ", triangle "
            << (gpuNearer ? g.triangle : et) << ") is not on the ray; " << x.outside << " outside";
        const bool atEdge = x.edge <= 10.0 * x.tolerance;
        const bool atLimit =
            std::abs(x.t - r.tMin) <= 1e-5 * std::abs(x.t) || std::abs(x.t - r.tMax) <= 1e-5 * std::abs(x.t);
        ASSERT_TRUE(atEdge || atLimit) << where() << ": GPU " << (g.closest ? std::to_string(g.t) : "miss")
                                       << ", Embree " << (embreeHit ? std::to_string(e.t) : "miss")
                                       << ", the nearer hit is not at an edge (" << x.edge << " from one)";
        ++(gpuNearer ? tally.embreeSlipped : tally.gpuSlipped);
    }
}

void runScene(const core::Scene& scene, gl::RayStage stage, int count, unsigned seed)
{
    const gl::RayCaster caster(scene);
    gl::RayBatch batch;
    const std::vector<gl::BatchRay> rays = testRays(scene, count, seed);
    const std::vector<gl::BatchResult> gpu = batch.run(caster, rays, stage);
    Tally tally;
    compareWithEmbree(scene, rays, gpu, tally);
    // Rays that disagree are the rare ones through an edge, not a systematic difference.
    EXPECT_GT(tally.hits, tally.rays / 4) << scene.name;
    // A third of the rays aim at a vertex or an edge, where ties between triangles are the rule. Most
    // edges of the Cornell box are open or silhouettes (blocks on the floor, walls that meet without
    // sharing vertices), where a ray rounded past the edge rightly misses it; through shared edges the
    // GPU walk is watertight (core's RaysThroughSharedEdgesAndVerticesNeverSlipThrough).
    EXPECT_LT(tally.sharedEdge + tally.embreeSlipped + tally.gpuSlipped, tally.rays / 5) << scene.name;
    EXPECT_LE(tally.gpuSlipped + tally.anyDisagrees, tally.rays / 50) << scene.name;
    std::printf("%s (%s): %d rays, %d hits; at an edge: %d the other triangle, %d Embree went through, %d the GPU "
                "went through; anyHit differs at an edge: %d\n",
                scene.name.c_str(), stage == gl::RayStage::Compute ? "compute" : "fragment", tally.rays, tally.hits,
                tally.sharedEdge, tally.embreeSlipped, tally.gpuSlipped, tally.anyDisagrees);
}

TEST_F(RaycastTest, ComputeShaderMatchesEmbreeOnCornellVariants)
{
    for (const std::string& name : core::builtinSceneNames())
        runScene(core::makeCornell(name), gl::RayStage::Compute, 3000, 1);
}

TEST_F(RaycastTest, FragmentShaderMatchesEmbreeOnCornellVariants)
{
    for (const std::string& name : core::builtinSceneNames())
        runScene(core::makeCornell(name), gl::RayStage::Fragment, 3000, 2);
}

TEST_F(RaycastTest, ComputeShaderMatchesEmbreeOnTheTeapot)
{
    runScene(core::makeTeapotScene(), gl::RayStage::Compute, 4000, 3);
}

TEST_F(RaycastTest, FragmentShaderMatchesEmbreeOnTheTeapot)
{
    runScene(core::makeTeapotScene(), gl::RayStage::Fragment, 4000, 4);
}

// The GPU walk is the CPU walk of core::Bvh (which the core tests hold against brute force), operation for
// operation: the same triangle, t and barycentrics bit for bit and the same anyHit, also through edges and
// vertices, where one rounding decides between two triangles. Twice: as the driver divides, and from
// quotients one ulp off (RAYCAST_INEXACT_DIVISION), as a GPU's a / b may be (NVIDIA's was: an H100 picked
// other triangles than the CPU at edges), which the walk's own division must correct.
void expectCpuWalk(const core::Scene& scene, const std::vector<gl::BatchRay>& rays)
{
    const gl::RayCaster caster(scene);
    std::vector<gl::Define> defines = caster.defines();
    for (const bool inexact : {false, true}) {
        if (inexact) defines.push_back({"RAYCAST_INEXACT_DIVISION", "1"});
        gl::RayBatch batch(defines);
        for (gl::RayStage stage : {gl::RayStage::Compute, gl::RayStage::Fragment}) {
            SCOPED_TRACE(std::string(stage == gl::RayStage::Compute ? "compute" : "fragment") +
                         (inexact ? ", a quotient one ulp off" : ""));
            const std::vector<gl::BatchResult> gpu = batch.run(caster, rays, stage);
            int differ = 0;
            for (std::size_t i = 0; i < rays.size() && differ < 5; ++i) {
                const gl::BatchRay& r = rays[i];
                core::RayHit h;
                const bool hit = caster.bvh().closestHit(r.origin, r.dir, r.tMin, r.tMax, h);
                const bool any = caster.bvh().anyHit(r.origin, r.dir, r.tMin, r.tMax);
                const bool same = bool(gpu[i].closest) == hit && bool(gpu[i].any) == any &&
                                  (!hit || (gpu[i].triangle == h.triangle && gpu[i].t == h.t && gpu[i].b1 == h.b1 &&
                                            gpu[i].b2 == h.b2));
                if (same) continue;
                ++differ;
                ADD_FAILURE() << scene.name << " ray " << i << ": GPU " << (gpu[i].closest ? "hit" : "missed")
                              << " triangle " << gpu[i].triangle << " t " << gpu[i].t << " b " << gpu[i].b1 << ","
                              << gpu[i].b2 << " any " << gpu[i].any << "; CPU " << (hit ? "hit" : "missed")
                              << " triangle " << h.triangle << " t " << h.t << " b " << h.b1 << "," << h.b2 << " any "
                              << any;
            }
        }
    }
}

// A single ray and a 3x5 batch (a fragment viewport of 15 x 1).
TEST_F(RaycastTest, TinyBatchesMatchTheCpuWalk)
{
    const core::Scene scene = core::makeCornell("cornell-slats");
    for (int n : {1, 15}) expectCpuWalk(scene, testRays(scene, n, 9));
}

TEST_F(RaycastTest, GpuWalkIsTheCpuWalkBitForBitOnCornellVariants)
{
    for (const std::string& name : core::builtinSceneNames()) {
        const core::Scene scene = core::makeCornell(name);
        expectCpuWalk(scene, testRays(scene, 1000, 11));
    }
}

// A scene with no triangles: one empty leaf, no hits, nothing read out of bounds.
TEST_F(RaycastTest, EmptySceneMissesEverything)
{
    core::Scene scene;
    scene.materials.emplace_back();
    const gl::RayCaster caster(scene);
    gl::RayBatch batch;
    std::vector<gl::BatchRay> rays(3);
    rays[0] = {{0, 0, 0}, 0.0f, {0, 0, 1}, kInf};
    rays[1] = {{1, 2, 3}, 0.0f, {-1, 0, 0}, 10.0f};
    rays[2] = {{0, 0, 0}, 0.0f, {0, 1, 0}, kInf};
    for (gl::RayStage stage : {gl::RayStage::Compute, gl::RayStage::Fragment})
        for (const gl::BatchResult& r : batch.run(caster, rays, stage)) {
            EXPECT_EQ(r.closest, 0u);
            EXPECT_EQ(r.any, 0u);
        }
}

} // namespace
} // namespace bounce
