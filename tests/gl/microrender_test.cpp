// Micro-rendering (gl/technique/microrender/): the point hierarchy's invariants on the GPU-built tree (the
// leaves' areas sum to the mesh area, every sphere and normal cone contains its children's, the stackless
// walk takes every leaf once), the furnace (rho L with and without importance warping), a closed scene
// leaves no micro-pixel empty with ray casting on, the path tracer's one bounce on cornell-spot and
// cornell-point, the glossy case, and the named hard cases. Tiny images: llvmpipe on two cores.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/image.h"
#include "core/metrics.h"
#include "gl/frame/frame.h"
#include "gl/frame/points/point_cloud.h"
#include "gl/resource/timer.h"
#include "gl/technique/microrender/point_hierarchy.h"
#include "tests/form_factor.h"
#include "tests/gl/gl_test_fixture.h"
#include "tests/gl/point_test_util.h"
#include "tests/image_expect.h"

namespace bounce {
namespace {

using testing::allFiniteNonNegative;
using testing::halfToFloat;
using testing::interiorOf;
using testing::meanOver;
using testing::PointRender;
using testing::renderPoints;
using testing::versus;
using testing::Versus;

class MicrorenderTest : public GlTest {};

// An 8 x 8 frame of `scene` with its shadow maps, and the point cloud of `points` points lit through them
// with its hierarchy built.
struct LitHierarchy {
    static gl::FrameSettings settings(int shadowMapSize)
    {
        gl::FrameSettings fs;
        fs.width = 8;
        fs.height = 8;
        fs.shadowMapSize = shadowMapSize;
        return fs;
    }
    LitHierarchy(const core::Scene& scene, int points, int shadowMapSize)
        : frame(scene, settings(shadowMapSize)), cloud(frame, points, 1, false), hierarchy(cloud)
    {
        gl::PassTimers timers;
        frame.beginFrame();
        frame.renderShadowMaps(timers);
        cloud.update(frame, timers);
        cloud.light(frame, timers);
        hierarchy.build(cloud, timers);
    }
    gl::Frame frame;
    gl::PointCloud cloud;
    gl::PointHierarchy hierarchy;
};

TEST_F(MicrorenderTest, HierarchyAreasSpheresAndConesContainTheirChildren)
{
    const core::Scene scene = core::makeCornell("cornell-slats");
    LitHierarchy lit(scene, 4096, 256);
    const gl::PointHierarchy& hierarchy = lit.hierarchy;
    const std::vector<gl::GpuMicroNode> nodes = hierarchy.nodes().download<gl::GpuMicroNode>();
    const int n = hierarchy.leafCount();
    ASSERT_EQ(int(nodes.size()), 2 * n);

    double meshArea = 0.0;
    for (double a : core::triangleAreas(scene)) meshArea += a;
    double leafArea = 0.0;
    for (int j = 0; j < n; ++j) leafArea += nodes[n + j].areaM2;
    EXPECT_NEAR(leafArea, meshArea, 1e-4 * meshArea) << "the leaves' areas";
    EXPECT_NEAR(nodes[1].areaM2, meshArea, 1e-3 * meshArea) << "the root's area";

    int sphereFails = 0, coneFails = 0, radianceFails = 0;
    for (int i = 1; i < n; ++i) {
        const gl::GpuMicroNode& p = nodes[i];
        for (int c : {2 * i, 2 * i + 1}) {
            const gl::GpuMicroNode& k = nodes[c];
            const float reach = glm::length(glm::vec3(k.sphere) - glm::vec3(p.sphere)) + k.sphere.w;
            if (reach > p.sphere.w * (1.0f + 1e-5f) + 1e-6f) ++sphereFails;
            if (p.cone.w < 3.14159f) {
                const float angle = std::acos(std::clamp(glm::dot(glm::vec3(p.cone), glm::vec3(k.cone)), -1.0f, 1.0f));
                if (angle + k.cone.w > p.cone.w + 2e-3f) ++coneFails;
            }
        }
        // The aggregated radiance lies between the children's (an area-weighted mean).
        for (int ch = 0; ch < 3; ++ch) {
            const auto comp = [&](const gl::GpuMicroNode& x) {
                const std::uint32_t w = x.radiance[ch / 2];
                return halfToFloat(ch % 2 == 0 ? (w & 0xFFFFu) : (w >> 16));
            };
            const float a = comp(nodes[2 * i]), b = comp(nodes[2 * i + 1]), m = comp(p);
            if (m < std::min(a, b) * (1.0f - 2e-3f) - 1e-6f || m > std::max(a, b) * (1.0f + 2e-3f) + 1e-6f)
                ++radianceFails;
        }
    }
    EXPECT_EQ(sphereFails, 0) << "spheres that do not contain a child's";
    EXPECT_EQ(coneFails, 0) << "normal cones that do not contain a child's";
    EXPECT_EQ(radianceFails, 0) << "aggregated radiance outside the children's";
}

// Deforming geometry (§2.1, "Deforming and Moving Geometry"): the hierarchy stays and its nodes are refitted.
// The furnace box stretched to twice its depth: the points ride on their triangles, and their areas scale
// with them ("we scale the points' radii to compensate for the varying point densities"): a point on a
// wall along z has twice its area at rest, one on the walls across z the same, and the leaves sum to the
// stretched box's 10 m^2 (6 before; within 0.5%: the sampler gives each triangle a whole number of points);
// every node's sphere still contains its children's. The hard case of a box flattened to its floor: the
// walls' triangles have no area left, nor their points; those of the floor and the ceiling, now one on the
// other, keep theirs.
TEST_F(MicrorenderTest, DeformedGeometryRefitsTheHierarchyAndRescalesThePoints)
{
    const core::Scene scene = testing::pointFurnaceBox(0.5f, 1.0f);
    LitHierarchy lit(scene, 4096, 64);
    const int n = lit.hierarchy.leafCount();
    const std::vector<gl::GpuMicroNode> rest = lit.hierarchy.nodes().download<gl::GpuMicroNode>();
    const auto rebuild = [&](glm::vec3 scale) {
        const testing::MovedVertices v = testing::scaledVertices(scene, scale);
        EXPECT_TRUE(lit.frame.moveVertices(v.positions, v.normals));
        gl::PassTimers timers;
        lit.cloud.update(lit.frame, timers);
        lit.cloud.light(lit.frame, timers);
        lit.hierarchy.build(lit.cloud, timers);
        return lit.hierarchy.nodes().download<gl::GpuMicroNode>();
    };

    const std::vector<gl::GpuMicroNode> nodes = rebuild({1.0f, 1.0f, 2.0f});
    double leafArea = 0.0;
    int wrongAreas = 0, sphereFails = 0;
    for (int j = 0; j < n; ++j) {
        const gl::GpuMicroNode& leaf = nodes[n + j];
        leafArea += leaf.areaM2;
        const bool alongZ = std::abs(leaf.cone.z) < 0.5f; // the floor, the ceiling and the walls at x = 0, 1
        if (std::abs(leaf.areaM2 - rest[n + j].areaM2 * (alongZ ? 2.0f : 1.0f)) > 1e-4f * rest[n + j].areaM2)
            ++wrongAreas;
    }
    for (int i = 1; i < n; ++i)
        for (int c : {2 * i, 2 * i + 1}) {
            const float reach =
                glm::length(glm::vec3(nodes[c].sphere) - glm::vec3(nodes[i].sphere)) + nodes[c].sphere.w;
            if (reach > nodes[i].sphere.w * (1.0f + 1e-5f) + 1e-6f) ++sphereFails;
        }
    EXPECT_NEAR(leafArea, 10.0, 0.05) << "the stretched box's area";
    EXPECT_NEAR(nodes[1].areaM2, leafArea, 1e-4 * leafArea) << "the root's area";
    EXPECT_EQ(wrongAreas, 0) << "points whose area did not follow their triangle's";
    EXPECT_EQ(sphereFails, 0) << "spheres that do not contain a child's";
    EXPECT_GT(nodes[1].sphere.w, 1.1f * rest[1].sphere.w) << "the root's sphere follows the stretched box";

    const std::vector<gl::GpuMicroNode> flat = rebuild({1.0f, 0.0f, 1.0f});
    int wrongFlat = 0;
    bool finite = true;
    for (int j = 0; j < n; ++j) {
        const bool floorOrCeiling = std::abs(rest[n + j].cone.y) > 0.5f;
        const float want = floorOrCeiling ? rest[n + j].areaM2 : 0.0f;
        if (std::abs(flat[n + j].areaM2 - want) > 1e-4f * rest[n + j].areaM2) ++wrongFlat;
        finite = finite && std::isfinite(flat[n + j].sphere.x) && std::isfinite(flat[n + j].sphere.w);
    }
    EXPECT_TRUE(finite);
    EXPECT_EQ(wrongFlat, 0) << "flattened: the walls' points with area left, or the floor's and ceiling's without";

    // Nothing moves for counts that are not the scene's or a position that is not finite.
    testing::MovedVertices bad = testing::scaledVertices(scene, glm::vec3(1.0f));
    bad.positions[3].x = NAN;
    const gl::FrameVersion before = lit.frame.version();
    EXPECT_FALSE(lit.frame.moveVertices(bad.positions, bad.normals));
    bad.positions.pop_back();
    EXPECT_FALSE(lit.frame.moveVertices(bad.positions, bad.normals));
    EXPECT_TRUE(lit.frame.version() == before);
}

// The points' glossy lobes (point_cloud.glsl's `glossy`) on cornell-glossy, against the emitter's closed
// form: on the metal block's top face, which sees the whole emitter and nothing between, the lobe's
// irradiance is L pi F with F the form factor to a parallel rectangle (Howell C-11), its direction points
// at the emitter, its F0 is the block's (1) and its alpha the block's 0.09 widened by the emitter's extent
// (point_light.glsl's widenedAlpha: alpha'^2 = alpha^2 + m / 4, m the mean squared angle between the
// directions the light comes from and their mean, here integrated over the rectangle; the shader takes
// each triangle as a disc, hence 0.02 in sqrt(alpha')); the diffuse walls (weight 0) carry no lobe; and
// every interior node's lobe irradiance is the area-weighted mean of its children's.
TEST_F(MicrorenderTest, GlossyLobesAtThePointsAndNodesMatchTheEmittersClosedForm)
{
    const core::Scene scene = core::makeCornell("cornell-glossy");
    LitHierarchy lit(scene, 16384, 1024);
    const gl::PointCloud& cloud = lit.cloud;
    const gl::PointHierarchy& hierarchy = lit.hierarchy;
    ASSERT_TRUE(cloud.glossy());

    const std::vector<testing::PointSurfel> surfels = cloud.surfels().download<testing::PointSurfel>();
    const std::vector<glm::uvec4> lobes = cloud.glossyLobes().download<glm::uvec4>();
    ASSERT_EQ(surfels.size(), lobes.size());
    const auto irradiance = [](const glm::uvec4& g) {
        return glm::vec3(halfToFloat(g.y & 0xFFFFu), halfToFloat(g.y >> 16), halfToFloat(g.z & 0xFFFFu));
    };
    const auto direction = [](std::uint32_t v) { // common/packing.glsl's octDecode of two snorm16
        glm::vec2 e(std::max(float(std::int16_t(v & 0xFFFFu)) / 32767.0f, -1.0f),
                    std::max(float(std::int16_t(v >> 16)) / 32767.0f, -1.0f));
        glm::vec3 n(e, 1.0f - std::abs(e.x) - std::abs(e.y));
        if (n.z < 0.0f)
            n = glm::vec3((1.0f - std::abs(n.y)) * (n.x >= 0.0f ? 1.0f : -1.0f),
                          (1.0f - std::abs(n.x)) * (n.y >= 0.0f ? 1.0f : -1.0f), n.z);
        return glm::normalize(n);
    };
    const glm::vec3 radiance(17.0f, 12.0f, 4.0f), centre(0.278f, 0.5487f, 0.2795f);
    // The metal's alpha widened by the mean squared angle of the emitter's directions seen from p, weighted
    // by what each brings (cos cos / r^2), on a 64 x 64 grid over the rectangle.
    const auto widenedAlpha = [](const glm::dvec3& p) {
        std::vector<std::pair<glm::dvec3, double>> dirs;
        glm::dvec3 sum(0.0);
        double total = 0.0;
        for (int j = 0; j < 64; ++j)
            for (int i = 0; i < 64; ++i) {
                const glm::dvec3 q(0.213 + 0.130 * (i + 0.5) / 64.0, 0.5487, 0.227 + 0.105 * (j + 0.5) / 64.0);
                const glm::dvec3 d = q - p;
                const double r2 = glm::dot(d, d), c = d.y / std::sqrt(r2);
                dirs.push_back({d / std::sqrt(r2), c * c / r2});
                sum += dirs.back().first * dirs.back().second;
                total += dirs.back().second;
            }
        const glm::dvec3 mean = glm::normalize(sum);
        double m = 0.0;
        for (const auto& [d, w] : dirs) m += w * std::pow(std::acos(std::min(glm::dot(d, mean), 1.0)), 2.0);
        return std::sqrt(0.09 * 0.09 + m / total / 4.0);
    };
    int top = 0, topFails = 0, directionFails = 0, materialFails = 0, walls = 0, wallFails = 0;
    double worst = 0.0;
    float roughest = 0.0f, smoothest = 1.0f;
    for (std::size_t i = 0; i < surfels.size(); ++i) {
        const testing::PointSurfel& s = surfels[i];
        const glm::vec3 e = irradiance(lobes[i]);
        if ((s.diffuse >> 24) == 0u) { // weight 0: a diffuse wall
            ++walls;
            if (e != glm::vec3(0.0f)) ++wallFails;
            continue;
        }
        if (s.normal.y < 0.999f || std::abs(s.position.y - 0.330f) > 1e-3f) continue;
        ++top;
        const double f = testing::rectFormFactor(0.213 - s.position.x, 0.343 - s.position.x, 0.227 - s.position.z,
                                                 0.332 - s.position.z, 0.5487 - s.position.y);
        for (int c = 0; c < 3; ++c) {
            const double want = radiance[c] * M_PI * f, err = std::abs(e[c] - want) / want;
            worst = std::max(worst, err);
            if (err > 0.02) ++topFails;
        }
        const float angle =
            std::acos(std::min(glm::dot(direction(lobes[i].x), glm::normalize(centre - s.position)), 1.0f));
        if (angle > 0.05f) ++directionFails;
        const float roughness = float(lobes[i].w >> 24) / 255.0f;
        roughest = std::max(roughest, roughness);
        smoothest = std::min(smoothest, roughness);
        if ((lobes[i].w & 0xFFFFFFu) != 0xFFFFFFu ||
            std::abs(roughness - std::sqrt(widenedAlpha(glm::dvec3(s.position)))) > 0.02)
            ++materialFails;
    }
    std::printf("[ lobes    ] %d points on the block's top, largest irradiance error %.4f, sqrt(alpha) %.3f to %.3f; "
                "%d on diffuse walls\n",
                top, worst, smoothest, roughest, walls);
    ASSERT_GT(top, 20);
    ASSERT_GT(walls, 8000);
    EXPECT_EQ(topFails, 0) << "the top's glossy irradiance against L pi F";
    EXPECT_EQ(directionFails, 0) << "lobe directions more than 0.05 rad from the emitter's centre";
    EXPECT_EQ(materialFails, 0) << "F0 and the widened sqrt(alpha) of the metal";
    EXPECT_EQ(wallFails, 0) << "diffuse points that carry a glossy lobe";

    struct GlossyNode {
        gl::GpuMicroNode node;
        glm::uvec4 glossy;
    };
    static_assert(sizeof(GlossyNode) == 64, "hierarchy.glsl's MicroNode with GLOSSY_POINTS");
    ASSERT_EQ(hierarchy.nodeBytes(), sizeof(GlossyNode));
    const std::vector<GlossyNode> nodes = hierarchy.nodes().download<GlossyNode>();
    const int n = hierarchy.leafCount();
    ASSERT_EQ(int(nodes.size()), 2 * n);
    int meanFails = 0;
    for (int i = 1; i < n; ++i) {
        const GlossyNode &a = nodes[2 * i], &b = nodes[2 * i + 1];
        const float wa = a.node.areaM2 / (a.node.areaM2 + b.node.areaM2);
        const glm::vec3 want = wa * irradiance(a.glossy) + (1.0f - wa) * irradiance(b.glossy);
        const glm::vec3 got = irradiance(nodes[i].glossy);
        for (int c = 0; c < 3; ++c)
            if (std::abs(got[c] - want[c]) > 2e-3f * want[c] + 1e-6f) ++meanFails;
    }
    EXPECT_EQ(meanFails, 0) << "interior nodes whose lobe irradiance is not their children's area-weighted mean";
}

// gather.comp's stackless depth-first walk of one subtree (heap indices, skip pointers computed on the
// fly), the same loop in C++: every leaf under the root is taken by exactly one node of the cut, whatever
// decides the descent.
std::vector<int> walkTakes(int leafCount, int start, const std::function<bool(std::uint32_t)>& descend)
{
    std::vector<int> taken(leafCount, 0);
    std::uint32_t node = std::uint32_t(start);
    while (true) {
        const bool leaf = node >= std::uint32_t(leafCount);
        if (!leaf && descend(node)) {
            node = 2u * node;
            continue;
        }
        std::uint32_t lo = node, hi = node; // the leaves under it
        while (lo < std::uint32_t(leafCount)) lo = 2u * lo, hi = 2u * hi + 1u;
        for (std::uint32_t l = lo; l <= hi; ++l) ++taken[l - leafCount];
        while (node != std::uint32_t(start) && (node & 1u) == 1u) node >>= 1u;
        if (node == std::uint32_t(start)) break;
        node += 1u;
    }
    return taken;
}

TEST(MicrorenderWalk, ACutNeverTakesALeafTwice)
{
    constexpr int n = 1024, group = 64;
    for (int trial = 0; trial < 3; ++trial) {
        std::vector<int> total(n, 0);
        for (int g = 0; g < group; ++g) {
            const auto t = walkTakes(n, group + g, [&](std::uint32_t node) {
                return trial == 0 || (trial == 1 ? (node * 2654435761u >> 7) % 3 != 0 : node < 200u);
            });
            for (int i = 0; i < n; ++i) total[i] += t[i];
        }
        for (int i = 0; i < n; ++i) ASSERT_EQ(total[i], 1) << "leaf " << i << ", trial " << trial;
    }
}

// Furnace: every point reflects rho L_e, so the gather returns rho (rho L_e) at every pixel, warped or not,
// with the rays through the triangles (the default). The paper's rays (rays=discs: against the listed
// leaves' discs only, none where the list is empty) leave the holes between nodes empty: light is lost
// there, as the paper says of any rasterisation ("a possibility that we miss small holes"), measured 5.8%
// on the mean and 17% at the worst pixel (4,994 empty micro-pixels of 82,944).
TEST_F(MicrorenderTest, FurnaceReturnsRhoLWithAndWithoutWarping)
{
    constexpr float rho = 0.5f, le = 1.0f;
    const double want = rho * rho * le;
    const core::Scene scene = testing::pointFurnaceBox(rho, le);
    for (const auto& [warp, rays] :
         {std::pair{"1", "triangles"}, std::pair{"0", "triangles"}, std::pair{"1", "discs"}}) {
        SCOPED_TRACE(std::string("warp=") + warp + " rays=" + rays);
        const PointRender r = renderPoints(
            scene, "microrender", {{"points", "4096"}, {"coarsestLevel", "0"}, {"warp", warp}, {"rays", rays}}, 12, 12);
        double lo = 1e30, hi = 0.0;
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 12; ++x) {
                lo = std::min(lo, double(r.indirect.at(x, y).x));
                hi = std::max(hi, double(r.indirect.at(x, y).x));
            }
        const double mean = meanOver(r.indirect, r.mask, 0);
        std::printf("[ furnace  ] warp=%s rays=%s: mean %.4f (closed form %.4f), min %.4f, max %.4f, %.0f empty\n",
                    warp, rays, mean, want, lo, hi, r.counter("emptyMicroPixels"));
        if (std::string(rays) == "discs") {
            // Holes only take light away: below the closed form, by less than 10% on the mean.
            EXPECT_LT(mean, want);
            EXPECT_GT(mean, 0.90 * want);
            EXPECT_LT(hi, 1.08 * want);
            EXPECT_GT(r.counter("emptyMicroPixels"), 0.0) << "the paper's rays fill no hole";
            EXPECT_GT(r.counter("rayPixels"), 0.0) << "no listed disc took a micro-pixel";
            continue;
        }
        // The points' diffuse colour is stored as 8 bits (0.5 -> 128/255, +0.4%) and the warp's weights sum
        // to rho within 3.5% for one jitter (tests/core/brdf_warp_test.cpp): 3% on the mean, 8% per pixel
        // (measured 0.2% on the mean, -3.4% / +4.2% per pixel).
        EXPECT_NEAR(mean, want, 0.03 * want);
        EXPECT_GT(lo, 0.92 * want);
        EXPECT_LT(hi, 1.08 * want);
        // A closed scene: with ray casting on, no micro-pixel is left empty.
        EXPECT_EQ(r.counter("emptyMicroPixels"), 0.0);
    }
}

// Against the path tracer's one bounce (onebounce-indirect, 8192 spp at 24 x 24: about 3% noise per pixel),
// gathering at every pixel with 24^2 warped micro-buffers and rays, on interior pixels. The paper's point
// rasterisation (silhouettes=off) dilates silhouettes by up to a micro-pixel (a pixel takes the nearest node
// whose centre falls in it, also when the surface covers a sliver of it): where surfaces border the void
// (the box's open front) or a darker surface behind, that adds light. The silhouette rays (the default)
// ray cast the micro-pixels the rasterised nodes do not fill or fill at different depths. Measured (mean
// ratio, relative RMSE) at cut 1, the paper's criterion: cornell-spot 1.022, 0.217 (silhouettes=off: 1.076,
// 0.248); cornell-point 1.037, 0.152 (1.072, 0.166). Without the depth test of the silhouette rays
// (silhouettes=coverage): cornell-spot 1.049, 0.229; with the depth test alone 1.043 and 1.051. With the
// paper's rays against the listed discs (rays=discs): 1.046, 0.198 and 1.039, 0.144.
// The gather point leaves its surface by a ray's offset (common/scene.glsl, surfaceRayOffset), whatever the
// points' size. Lifted by half a point's disc radius, as it was, a sparse cloud lifts it by centimetres: at
// 256 points on cornell-spot (discs of 4.9 cm) by 2.4 cm, and the blocks at the tall block's foot read
// 0.58-0.74 of the path tracer's light (on Sponza's 65,536 points, 7 cm: its indirect light read 1.047 of
// the path tracer's on a white copy, 1.011 with the ray's offset). Measured: relative RMSE of the 4x4-pixel
// block means of four frames' indirect light against the path tracer's one bounce at 32x32 (1024 spp),
// 0.0853 now, 0.1059 with the 2.4 cm lift.
TEST_F(MicrorenderTest, SparsePointsGatherFromTheSurfaceNotAboveIt)
{
    constexpr int size = 32, block = 4, blocks = size / block;
    const core::Scene scene = core::makeCornell("cornell-spot");
    const core::Image want = testing::pathTracedOneBounce(scene, size, size, 1024);
    // The still frames' mean (Renderer::image) less `direct`'s over the same frames: the indirect light of four
    // frames, as `bounce render --warmup 0 --frames 4` gives it.
    const auto stillMean = [&](const std::string& technique, const gl::ParamValues& values) {
        gl::Renderer r(scene, technique, gl::ParamValues(gl::frameParams()), values, size, size);
        for (int f = 0; f < 4; ++f) r.renderFrame();
        return r.image();
    };
    gl::ParamValues points(gl::findTechnique("microrender").params);
    points.setValue("points", 256);
    const core::Image all = stillMean("microrender", points), direct = stillMean("direct", gl::ParamValues());
    double se = 0.0, sum = 0.0;
    for (int by = 0; by < blocks; ++by)
        for (int bx = 0; bx < blocks; ++bx) {
            double a = 0.0, b = 0.0;
            for (int y = by * block; y < (by + 1) * block; ++y)
                for (int x = bx * block; x < (bx + 1) * block; ++x)
                    for (int c = 0; c < 3; ++c) {
                        a += all.at(x, y)[c] - direct.at(x, y)[c];
                        b += want.at(x, y)[c];
                    }
            se += (a - b) * (a - b);
            sum += b;
        }
    const double relative = std::sqrt(se / (blocks * blocks)) / (sum / (blocks * blocks));
    std::printf("[ vs ref   ] 256 points, 4x4-pixel blocks: relative RMSE %.4f\n", relative);
    EXPECT_LT(relative, 0.095);
}

TEST_F(MicrorenderTest, MatchesThePathTracersOneBounce)
{
    constexpr int size = 24;
    struct Case {
        const char* name;
        testing::Sets sets;
        double maxMean;
    };
    const Case cases[] = {
        {"silhouette rays", {{"rays", "triangles"}}, 1.045},
        {"point rasterisation", {{"rays", "triangles"}, {"silhouettes", "off"}}, 1.12},
        {"silhouette rays where the nodes do not fill a pixel", {{"silhouettes", "coverage"}}, 1.07},
        {"rays against discs", {{"rays", "discs"}}, 1.08},
    };
    for (const char* name : {"cornell-spot", "cornell-point"}) {
        const core::Scene scene = core::makeCornell(name);
        const core::Image want = testing::pathTracedOneBounce(scene, size, size, 8192);
        for (const Case& c : cases) {
            if (std::string(name) == "cornell-point" && &c != &cases[0]) continue; // the other two: once is enough
            SCOPED_TRACE(std::string(name) + ", " + c.name);
            testing::Sets sets = c.sets;
            sets.push_back({"coarsestLevel", "0"});
            sets.push_back({"cut", "1"});
            const PointRender r = renderPoints(scene, "microrender", sets, size, size);
            const std::vector<bool> mask = interiorOf(r.mask);
            ASSERT_GT(std::count(mask.begin(), mask.end(), true), size * size / 2);
            const Versus v = versus(r.indirect, want, mask);
            std::printf("[ vs ref   ] %s, %s: mean ratio %.4f, relative RMSE %.4f, rays in %.0f%% of the buffers\n",
                        name, c.name, v.meanRatio, v.relRmse, 100.0 * r.counter("rayCastShare"));
            if (c.maxMean > 1.1) {
                EXPECT_GT(v.meanRatio, 1.04) << "the dilation adds light";
            }
            EXPECT_GT(v.meanRatio, 0.97) << "the mean against the path tracer";
            EXPECT_LT(v.meanRatio, c.maxMean) << "the mean against the path tracer";
            EXPECT_LT(v.relRmse, 0.30) << "relative RMSE against the path tracer";
            if (::testing::Test::HasFailure())
                testing::writeComparisonImages(std::string(name) + "-" + c.sets.front().second, r.indirect, want);
        }
    }
}

// cornell-spot with every surface a rough dielectric (specular 1: F0 = 0.04, w = 1; roughness 1), as Sponza's
// materials are. Its diffuse lobe is (1 - w Fo)(1 - w Fi) c_diff / pi (core/brdf.h), and the points must send
// what that lets through (point_light.glsl): with c_diff / pi alone they sent 1.14 times as much, and the
// mean ratio was 1.128 (relative RMSE 0.318); with the interface's terms 1.025 (0.232).
TEST_F(MicrorenderTest, DielectricPointsSendWhatTheirInterfaceLetsThrough)
{
    constexpr int size = 24;
    core::Scene scene = core::makeCornell("cornell-spot");
    scene.name = "cornell-spot-dielectric";
    for (core::Material& m : scene.materials) m.specular = 1.0f;
    ASSERT_TRUE(scene.hasGlossy());
    const core::Image want = testing::pathTracedOneBounce(scene, size, size, 8192);
    const PointRender r = renderPoints(scene, "microrender", {{"coarsestLevel", "0"}}, size, size);
    const std::vector<bool> mask = interiorOf(r.mask);
    const Versus v = versus(r.indirect, want, mask);
    std::printf("[ vs ref   ] dielectric cornell-spot: mean ratio %.4f, relative RMSE %.4f\n", v.meanRatio, v.relRmse);
    EXPECT_GT(v.meanRatio, 0.97) << "the mean against the path tracer";
    EXPECT_LT(v.meanRatio, 1.05) << "the mean against the path tracer: the points' diffuse light through the interface";
    EXPECT_LT(v.relRmse, 0.30) << "relative RMSE against the path tracer";
}

// cornell-spot with every diffuse colour moved into a 1 x 1 base-colour texture (sRGB, 8 bits) under a white
// factor, as Sponza's materials are: the same scene to within the texture's rounding. Micro-rendering's rays
// (in every micro-pixel of the buffers with a post-traversal list, at holes and at silhouettes) must light
// their hits with the texel as the points do. Measured: mean ratio 0.993, relative RMSE 0.013; with the
// factor alone at the hits (white walls) 1.197, 0.300.
TEST_F(MicrorenderTest, RayHitsTakeTheBaseColourTexture)
{
    constexpr int size = 24;
    const core::Scene plain = core::makeCornell("cornell-spot");
    core::Scene textured = plain;
    auto encode = [](float c) {
        const float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
        return std::uint8_t(std::lround(255.0f * std::clamp(s, 0.0f, 1.0f)));
    };
    for (core::Material& m : textured.materials) {
        core::Texture t;
        t.name = m.name + "-colour";
        t.width = t.height = 1;
        t.rgba8 = {encode(m.baseColor.x), encode(m.baseColor.y), encode(m.baseColor.z), 255};
        m.baseColorTexture = int(textured.textures.size());
        textured.textures.push_back(t);
        m.baseColor = glm::vec3(1.0f);
    }
    for (core::Mesh& mesh : textured.meshes) mesh.uvs.assign(mesh.positions.size(), glm::vec2(0.5f));
    const testing::Sets sets = {{"coarsestLevel", "0"}};
    const PointRender a = renderPoints(plain, "microrender", sets, size, size);
    const PointRender b = renderPoints(textured, "microrender", sets, size, size);
    ASSERT_GT(b.counter("rayPixels"), 0.0);
    const std::vector<bool> mask = interiorOf(a.mask);
    const Versus v = versus(b.indirect, a.indirect, mask);
    std::printf("[ texture  ] textured against plain: mean ratio %.4f, relative RMSE %.4f\n", v.meanRatio, v.relRmse);
    EXPECT_NEAR(v.meanRatio, 1.0, 0.015) << "the rays' hits do not take the texture";
    EXPECT_LT(v.relRmse, 0.03);
}

// cornell-glossy: on the rough metal block (GGX alpha 0.09) the indirect light is the glossy reflection of
// the diffusely lit room, what the warped micro-buffers gather (the block cannot see itself). On the
// block's interior pixels at 24 x 24 (26 of them), measured mean ratio / relative RMSE: 1.019 / 0.155 with
// importance warping, 1.069 / 0.183 with the Nusselt mapping weighted by the BRDF (§2.3, Fig. 5: the warp
// spends the micro-pixels on the lobe); with the paper's point rasterisation (silhouettes=off, the dilation
// above) 1.166 / 0.263 and 1.276 / 0.500.
// Elsewhere the light -> metal -> wall paths come from the points' glossy lobes (point_cloud.glsl's
// `glossy`): on the room's interior pixels (372), measured 1.025 / 0.312 (silhouettes=off: 1.076 / 0.375);
// with points that reflect diffusely only, as they did before they carried their lobes, 0.652 / 1.255
// (the metal's light on the ceiling missing).
TEST_F(MicrorenderTest, GlossyGatherOnTheMetalBlockAndFromItMatchesThePathTracer)
{
    constexpr int size = 24;
    const core::Scene scene = core::makeCornell("cornell-glossy");
    const core::Image want = testing::pathTracedOneBounce(scene, size, size, 8192);
    double rmse[2] = {0.0, 0.0};
    for (int warp : {1, 0}) {
        const PointRender r =
            renderPoints(scene, "microrender", {{"coarsestLevel", "0"}, {"warp", std::to_string(warp)}}, size, size);
        const std::vector<bool> block = interiorOf(r.glossy);
        ASSERT_GT(std::count(block.begin(), block.end(), true), 8);
        const Versus v = versus(r.indirect, want, block);
        std::printf("[ glossy   ] warp=%d: block mean ratio %.4f, relative RMSE %.4f over %d pixels\n", warp,
                    v.meanRatio, v.relRmse, int(std::count(block.begin(), block.end(), true)));
        rmse[warp] = v.relRmse;
        if (warp) {
            EXPECT_NEAR(v.meanRatio, 1.0, 0.08);
            EXPECT_LT(v.relRmse, 0.22);
            const std::vector<bool> room = interiorOf(testing::without(r.mask, r.glossy));
            const Versus w = versus(r.indirect, want, room);
            std::printf("[ glossy   ] the room: mean ratio %.4f, relative RMSE %.4f over %d pixels\n", w.meanRatio,
                        w.relRmse, int(std::count(room.begin(), room.end(), true)));
            EXPECT_GT(w.meanRatio, 0.95) << "the light the metal block reflects onto the room is missing";
            EXPECT_LT(w.meanRatio, 1.06) << "the mean against the path tracer";
            EXPECT_LT(w.relRmse, 0.36);
        }
    }
    EXPECT_LT(rmse[1], 0.9 * rmse[0]) << "importance warping did not help the glossy gather";
}

// The cut's two walks (cutWalk): one subtree per invocation, or the whole group level by level from shared
// queues, with the default queues and with queues of 64 nodes, which overflow from the second level on
// (the children that do not fit are walked as subtrees). They take the same cut, and atomicMin keeps the
// nearest node of each micro-pixel in any order: the same nodes visited, rasterised and listed, the same
// rays, and the same image to the bit, at 24^2 (the queues share the ray pass's words), at the pixels and
// at the points of a second bounce.
TEST_F(MicrorenderTest, CutWalksBySubtreesAndByLevelsTakeTheSameCut)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    const testing::Sets base = {{"coarsestLevel", "1"}, {"points", "4096"}, {"bounces", "2"}, {"bounceNodes", "64"}};
    std::vector<PointRender> r;
    for (const testing::Sets& walk : {testing::Sets{{"cutWalk", "subtrees"}}, testing::Sets{{"cutWalk", "levels"}},
                                      testing::Sets{{"cutWalk", "levels"}, {"cutQueue", "64"}}}) {
        testing::Sets s = base;
        s.insert(s.end(), walk.begin(), walk.end());
        r.push_back(renderPoints(scene, "microrender", s, 16, 12));
    }
    ASSERT_GT(r[0].counter("rays"), 0.0);
    for (std::size_t i = 1; i < r.size(); ++i) {
        for (const char* c : {"nodesVisitedPerSample", "nodesRasterisedPerSample", "microBuffersWithRays", "rays",
                              "rayPixels", "emptyMicroPixels"})
            EXPECT_EQ(r[i].counter(c), r[0].counter(c)) << c << ", walk " << i;
        EXPECT_EQ(r[i].indirect.rgb, r[0].indirect.rgb) << "walk " << i;
    }
}

// The gather point in a corner, inside the bounding spheres of the nodes around it: a small micro-buffer
// (8^2: a post-traversal list of 64) and a fine cut (cut 0.05: every leaf above a twentieth of a micro-pixel
// is listed; about 24 / cut leaves near a corner whatever the point count) overflow the list there; the
// rays still find every surface (the leaves that did not fit are lit at the hit), so it stays finite and lit,
// with either kind of rays.
TEST_F(MicrorenderTest, HardCaseGatherPointInACornerOverflowsTheList)
{
    core::Scene scene = core::makeCornell("cornell-spot");
    scene.camera.position = {0.50f, 0.05f, 0.50f}; // near the floor, looking into the back-left corner
    scene.camera.forward = glm::normalize(glm::vec3(0.5496f, 0.0f, 0.5592f) - scene.camera.position);
    scene.camera.up = {0.0f, 1.0f, 0.0f};
    for (const char* rays : {"triangles", "discs"}) { // discs: an overflowed list takes the triangles' rays
        SCOPED_TRACE(std::string("rays=") + rays);
        const PointRender r = renderPoints(
            scene, "microrender",
            {{"coarsestLevel", "0"}, {"microBuffer", "8"}, {"points", "4096"}, {"cut", "0.05"}, {"rays", rays}}, 16,
            16);
        std::printf("[ corner   ] rays=%s: list overflows %.0f of %.0f micro-buffers, %.0f with rays\n", rays,
                    r.counter("listOverflows"), r.counter("gatherSamples"), r.counter("microBuffersWithRays"));
        EXPECT_TRUE(allFiniteNonNegative(r.indirect));
        EXPECT_GT(r.counter("listOverflows"), 0.0) << "the case did not overflow a list";
        EXPECT_GT(meanOver(r.indirect, r.mask, 0), 0.0);
    }
}

// Thin slats (cornell-slats), the light 1 mm under the ceiling, a 1 x 1 and a 3 x 5 viewport, two bounces:
// finite, non-negative, and two bounces at least as bright as one.
TEST_F(MicrorenderTest, HardCasesStayFinite)
{
    struct Case {
        const char* scene;
        int w, h;
        testing::Sets sets;
    };
    const std::vector<Case> cases = {
        {"cornell-slats", 12, 12, {{"points", "16384"}, {"microBuffer", "8"}}},
        {"cornell-point-ceiling", 12, 12, {{"points", "16384"}, {"microBuffer", "8"}}},
        {"cornell-spot", 1, 1, {{"points", "4096"}}},
        {"cornell-spot", 3, 5, {{"points", "4096"}, {"coarsestLevel", "0"}}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(std::string(c.scene) + " " + std::to_string(c.w) + "x" + std::to_string(c.h));
        const PointRender r = renderPoints(core::makeCornell(c.scene), "microrender", c.sets, c.w, c.h);
        EXPECT_TRUE(allFiniteNonNegative(r.indirect));
    }
    const core::Scene scene = core::makeCornell("cornell-spot");
    const testing::Sets base = {{"points", "4096"}, {"microBuffer", "8"}, {"bounceNodes", "256"}};
    testing::Sets two = base;
    two.push_back({"bounces", "2"});
    const PointRender one = renderPoints(scene, "microrender", base, 12, 12);
    const PointRender both = renderPoints(scene, "microrender", two, 12, 12);
    EXPECT_TRUE(allFiniteNonNegative(both.indirect));
    const double m1 = meanOver(one.indirect, one.mask, 0), m2 = meanOver(both.indirect, both.mask, 0);
    std::printf("[ bounces  ] one %.5f, two %.5f\n", m1, m2);
    EXPECT_GT(m2, 1.05 * m1) << "the second bounce adds light";
}

} // namespace
} // namespace bounce
