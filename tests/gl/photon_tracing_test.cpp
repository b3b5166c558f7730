// Photon tracing of the photon family (gl/technique/photon/photon_tracer.h) against closed forms: the
// power that leaves each kind of light (cornell-box.md's numbers), the furnace box's stored power
// rho / (1 - rho) times the emitted power, Russian roulette keeping the expected power, the photon map's
// order (Hilbert indices ascending, and the curve's own property) and its determinism.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "gl/frame/frame.h"
#include "gl/frame/ray_caster.h"
#include "gl/gl.h"
#include "gl/resource/program.h"
#include "gl/technique/photon/photon_tracer.h"
#include "tests/gl/gl_test_fixture.h"
#include "tests/gl/photon_test_scenes.h"

namespace bounce {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Traced {
    glm::dvec3 emitted{0.0}, stored{0.0};
    std::vector<gl::GpuPhoton> photons;
    int grown = 0;
};

Traced trace(const core::Scene& scene, const gl::PhotonTracerSettings& settings)
{
    photontest::TracedPhotons traced(scene, settings);
    const gl::PhotonTracer& tracer = traced.tracer;
    Traced t;
    t.emitted = tracer.emittedTotal();
    t.photons = tracer.downloadPhotons();
    for (const gl::GpuPhoton& p : t.photons) t.stored += glm::dvec3(glm::vec3(p.powerIndex));
    t.grown = tracer.grownTimes();
    return t;
}

void expectRgbNear(const glm::dvec3& got, const glm::dvec3& want, double relative)
{
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], relative * want[c]) << "channel " << c;
}

class PhotonTracingTest : public GlTest {};

// cornell-box.md: the spot's power is I 2 pi (1 - cos 45 deg) = (0.42704, 0.30144, 0.10048) W. Each
// photon carries the light's power over its photon count, so the sum is exact up to float rounding.
TEST_F(PhotonTracingTest, SpotEmitsItsPower)
{
    gl::PhotonTracerSettings s;
    s.photons = 4096;
    const Traced t = trace(core::makeCornell("cornell-spot"), s);
    std::printf("[ measured ] spot: emitted (%.5f, %.5f, %.5f) W\n", t.emitted.x, t.emitted.y, t.emitted.z);
    expectRgbNear(t.emitted, {0.42704, 0.30144, 0.10048}, 2e-4);
}

// A soft spot (inner cone 0.4 rad, outer 0.6): its power is I 2 pi ((1 - cos inner) + (cos inner - cos outer)
// / 3), glTF's falloff t^2 integrated over the cone. The directions are stratified along the cone's axis,
// on which alone the falloff depends, so the sum is a midpoint rule of that integral: within 1e-3. The
// photons carried 0.63 of it when their power held the falloff twice (photon_tracer.cpp).
TEST_F(PhotonTracingTest, SoftSpotEmitsItsPower)
{
    core::Scene scene = core::makeCornell("cornell-spot");
    core::Light& spot = scene.lights.at(0);
    spot.innerConeRad = 0.4f;
    spot.outerConeRad = 0.6f;
    const double ci = std::cos(0.4), co = std::cos(0.6);
    const glm::dvec3 want = 2.0 * kPi * ((1.0 - ci) + (ci - co) / 3.0) * glm::dvec3(spot.intensity);
    gl::PhotonTracerSettings s;
    s.photons = 4096;
    const Traced t = trace(scene, s);
    std::printf("[ measured ] soft spot: emitted (%.5f, %.5f, %.5f) W, the falloff's integral (%.5f, %.5f, %.5f)\n",
                t.emitted.x, t.emitted.y, t.emitted.z, want.x, want.y, want.z);
    expectRgbNear(t.emitted, want, 1e-3);
}

TEST_F(PhotonTracingTest, PointEmitsItsPower)
{
    gl::PhotonTracerSettings s;
    s.photons = 4096;
    const Traced t = trace(core::makeCornell("cornell-point"), s);
    std::printf("[ measured ] point: emitted (%.5f, %.5f, %.5f) W\n", t.emitted.x, t.emitted.y, t.emitted.z);
    expectRgbNear(t.emitted, {2.91603, 2.05837, 0.68612}, 2e-4);
}

// The area light: pi L A, with A the light quad's area from cornell-box.md's corners (0.13 x 0.105 m).
TEST_F(PhotonTracingTest, AreaLightEmitsPiLA)
{
    gl::PhotonTracerSettings s;
    s.photons = 4096;
    const Traced t = trace(core::makeCornell("cornell-area"), s);
    const double area = (0.343 - 0.213) * (0.332 - 0.227);
    const glm::dvec3 want = kPi * area * glm::dvec3(17.0, 12.0, 4.0);
    std::printf("[ measured ] area: emitted (%.5f, %.5f, %.5f) W, pi L A (%.5f, %.5f, %.5f)\n", t.emitted.x,
                t.emitted.y, t.emitted.z, want.x, want.y, want.z);
    expectRgbNear(t.emitted, want, 2e-4);
}

// A point light in a closed box of albedo rho: every photon reaches a wall at every bounce, so with
// Russian roulette the stored power (from the second surface on) is emitted x (rho + rho^2 + ...) =
// emitted x rho / (1 - rho) in expectation. 16384 paths at rho = 0.5: the standard error of the sum is
// about 1.1%; 4% is over 3 sigma. Without roulette it is exactly the truncated series.
TEST_F(PhotonTracingTest, FurnaceBoxStoresRhoOverOneMinusRho)
{
    const float rho = 0.5f;
    gl::PhotonTracerSettings s;
    s.photons = 16384;
    s.maxBounces = 64;
    const Traced rr = trace(photontest::closedBox(rho), s);
    const double want = rho / (1.0 - rho);
    std::printf("[ measured ] furnace, roulette: stored / emitted = %.4f (closed form %.4f), %zu photons\n",
                rr.stored.x / rr.emitted.x, want, rr.photons.size());
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rr.stored[c] / rr.emitted[c], want, 0.04 * want);

    s.russianRoulette = false;
    s.maxBounces = 8;
    const Traced all = trace(photontest::closedBox(rho), s);
    double series = 0.0;
    for (int k = 1; k < s.maxBounces; ++k) series += std::pow(double(rho), k);
    std::printf("[ measured ] furnace, no roulette: stored / emitted = %.6f (series %.6f)\n",
                all.stored.x / all.emitted.x, series);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(all.stored[c] / all.emitted[c], series, 1e-3 * series);
    // Roulette keeps the expected power: the two agree within its noise (the truncated tail is 0.8%).
    EXPECT_NEAR(rr.stored.x, all.stored.x / series * want, 0.05 * rr.stored.x);
}

// hilbert30 (glsl/technique/photon/photon.glsl) of `points` over the box [lo, lo + extent).
std::vector<std::uint32_t> hilbertKeys(const std::vector<glm::vec4>& points, glm::vec3 lo, glm::vec3 extent)
{
    gl::Buffer in = gl::Buffer::fromVector("test.hilbert.points", points);
    gl::Buffer out("test.hilbert.keys", points.size() * 4);
    gl::Program program = gl::Program::compute("test.hilbertKeys", "test/hilbert_keys.comp");
    in.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    out.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    program.set("pointCount", unsigned(points.size()));
    program.set("boundsLo", lo);
    program.set("boundsExtent", extent);
    program.use();
    glDispatchCompute(GLuint((points.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    return out.download<std::uint32_t>();
}

// The Hilbert curve's defining property, checked without a second implementation of it: the cells of
// the 64^3 corner block of the 1024^3 grid (a cube of the curve's fifth level) get 64^3 consecutive
// indices, and cells with consecutive indices share a face.
TEST_F(PhotonTracingTest, HilbertOrderWalksFromFaceToFace)
{
    const int n = 64;
    std::vector<glm::vec4> centres;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) centres.emplace_back(x + 0.5f, y + 0.5f, z + 0.5f, 0.0f);
    const std::vector<std::uint32_t> keys = hilbertKeys(centres, glm::vec3(0.0f), glm::vec3(1024.0f));
    std::vector<std::pair<std::uint32_t, int>> order;
    for (std::size_t i = 0; i < keys.size(); ++i) order.push_back({keys[i], int(i)});
    std::sort(order.begin(), order.end());
    EXPECT_EQ(order.back().first - order.front().first, std::uint32_t(n * n * n - 1)) << "one range of the curve";
    int gaps = 0, jumps = 0;
    for (std::size_t i = 1; i < order.size(); ++i) {
        gaps += order[i].first != order[i - 1].first + 1;
        const glm::ivec3 a(centres[order[i - 1].second]), b(centres[order[i].second]);
        const glm::ivec3 d = glm::abs(a - b);
        jumps += d.x + d.y + d.z != 1;
    }
    EXPECT_EQ(gaps, 0);
    EXPECT_EQ(jumps, 0) << "consecutive cells that do not share a face";
}

// Paths traced twice give the same photons bit for bit (appended in any order, placed in path order,
// then sorted stably), in ascending Hilbert order over the tracer's bounds.
TEST_F(PhotonTracingTest, PhotonMapIsDeterministicAndInHilbertOrder)
{
    gl::PhotonTracerSettings s;
    s.photons = 8192;
    s.kdOrder = false;
    const core::Scene scene = core::makeCornell("cornell-spot");
    const Traced a = trace(scene, s), b = trace(scene, s);
    ASSERT_GT(a.photons.size(), 1000u);
    ASSERT_EQ(a.photons.size(), b.photons.size());
    EXPECT_EQ(std::memcmp(a.photons.data(), b.photons.data(), a.photons.size() * sizeof(gl::GpuPhoton)), 0);
    const core::Bounds bounds = scene.bounds();
    const float size = glm::length(bounds.extent());
    const glm::vec3 lo = bounds.lo - 1e-3f * size, extent = bounds.extent() + 2e-3f * size;
    std::vector<glm::vec4> positions;
    for (const gl::GpuPhoton& p : a.photons) positions.push_back(glm::vec4(glm::vec3(p.positionPath), 1.0f));
    const std::vector<std::uint32_t> keys = hilbertKeys(positions, lo, extent);
    int outOfOrder = 0;
    for (std::size_t i = 1; i < keys.size(); ++i) outOfOrder += keys[i] < keys[i - 1];
    EXPECT_EQ(outOfOrder, 0);
}

// A sun that shines into the Cornell box through its open front, at a slant: photons from the whole square
// across the scene (the slower, independent path: most of them meet the outside of the one-sided walls
// and are absorbed; together they carry E times the square's area), photons from the cells of the
// projection map, and photons from those cells weighted by what a pilot trace stored from each (guided
// emission: cells whose photons meet the outside of the box send fewer) store the same power, within the
// noise of the fewer photons that enter, while the projection map stores several times as many as the
// square and guided emission more again. Guided emission's photons still carry E times the marked
// cells' area together, each cell's share divided among its copies. The sun's paths meet no Russian
// roulette at their first surface (firstSurfaceRoulette); with it, fewer photons store the same power.
TEST_F(PhotonTracingTest, ProjectionMapSendsThePhotonsWhereTheSceneIs)
{
    core::Scene scene = core::makeCornell("cornell-spot");
    core::Light sun;
    sun.type = core::LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.2f, -0.6f, 1.0f));
    sun.intensity = glm::vec3(1.0f, 0.8f, 0.6f);
    scene.lights = {sun};
    gl::PhotonTracerSettings s;
    s.photons = 65536;
    s.guidedEmission = false;
    s.projectionMap = false;
    const Traced square = trace(scene, s);
    s.projectionMap = true;
    const Traced map = trace(scene, s);
    s.guidedEmission = true;
    const Traced guided = trace(scene, s);
    s.firstSurfaceRoulette = gl::kRouletteEveryLight;
    const Traced rouletted = trace(scene, s);
    std::printf("[ measured ] sun through the open front: %zu photons stored from the square, %zu from the "
                "projection map, %zu guided; stored power (%.5f, %.5f, %.5f), (%.5f, %.5f, %.5f) and (%.5f, %.5f, "
                "%.5f) W; emitted (%.5f, %.5f, %.5f) and guided (%.5f, %.5f, %.5f) W\n",
                square.photons.size(), map.photons.size(), guided.photons.size(), square.stored.x, square.stored.y,
                square.stored.z, map.stored.x, map.stored.y, map.stored.z, guided.stored.x, guided.stored.y,
                guided.stored.z, map.emitted.x, map.emitted.y, map.emitted.z, guided.emitted.x, guided.emitted.y,
                guided.emitted.z);
    EXPECT_GT(map.photons.size(), 3 * square.photons.size());
    // Measured: 28,888, 92,309 and 119,866 photons (the box's front faces fill most marked cells already).
    EXPECT_GT(double(guided.photons.size()), 1.2 * double(map.photons.size()));
    // Roulette at the first surface ends about 1 - albedo of the guided paths before they store anything
    // (measured: 84,375 photons against 119,866), with the same expected power.
    std::printf("[ measured ] guided with Russian roulette at the first surface: %zu photons, stored power (%.5f, "
                "%.5f, %.5f) W\n",
                rouletted.photons.size(), rouletted.stored.x, rouletted.stored.y, rouletted.stored.z);
    EXPECT_GT(double(guided.photons.size()), 1.25 * double(rouletted.photons.size()));
    expectRgbNear(map.stored, square.stored, 0.04);
    expectRgbNear(guided.stored, square.stored, 0.04);
    expectRgbNear(rouletted.stored, square.stored, 0.04);
    expectRgbNear(guided.emitted, map.emitted, 0.01);
    // The square's photons carry E times its area, (2 R)^2 with R the scene's bounding radius (x 1.01).
    const double side = 1.01 * glm::length(scene.bounds().extent());
    expectRgbNear(square.emitted, glm::dvec3(sun.intensity) * side * side, 1e-4);
}

// Guided emission's weights: kCopiesAtMean copies at the mean, in proportion around it, at least one
// (a cell that stored nothing still sends photons: the estimate stays unbiased) and at most kMaxCopies;
// nothing stored anywhere (a sun that misses the scene) leaves every cell one copy; and the emission list
// repeats each cell by its copies with the count in the entry's high bits.
TEST(PhotonGuidedEmission, CopiesFollowTheStoredPhotonsWithinTheirBounds)
{
    const std::vector<std::uint32_t> copies = gl::guidedCopies({0.0, 1.0, 2.0, 1.0, 1000.0});
    // The mean is 200.8: 1 photon is 1 / 200.8 of it, 1000 photons 4.98 times it.
    EXPECT_EQ(copies,
              (std::vector<std::uint32_t>{1, 1, 1, 1, std::uint32_t(std::lround(gl::kCopiesAtMean * 1000.0 / 200.8))}));
    const std::vector<std::uint32_t> even = gl::guidedCopies({3.0, 3.0, 3.0});
    for (std::uint32_t k : even) EXPECT_EQ(k, std::uint32_t(gl::kCopiesAtMean));
    EXPECT_EQ(gl::guidedCopies({0.0, 0.0}), (std::vector<std::uint32_t>{1, 1}));
    std::vector<double> oneHot(4096, 0.0);
    oneHot[7] = 5.0;
    EXPECT_EQ(gl::guidedCopies(oneHot)[7], gl::ProjectionMap::kMaxCopies);
    gl::ProjectionMap m;
    m.cells = {5, 9};
    EXPECT_EQ(m.entries(), (std::vector<std::uint32_t>{5u | 1u << 16, 9u | 1u << 16}));
    m.copies = {2, 1};
    EXPECT_EQ(m.entries(), (std::vector<std::uint32_t>{5u | 2u << 16, 5u | 2u << 16, 9u | 1u << 16}));
}

// Photons that reach the light (here: the back of the one-sided emitter, and its front) are absorbed:
// none lies on the emitting quad's plane between its corners.
TEST_F(PhotonTracingTest, NoPhotonIsStoredOnTheEmitter)
{
    gl::PhotonTracerSettings s;
    s.photons = 8192;
    const Traced t = trace(core::makeCornell("cornell-area"), s);
    int onLight = 0;
    for (const gl::GpuPhoton& p : t.photons) {
        const glm::vec3 x(p.positionPath);
        onLight += std::abs(x.y - 0.5487f) < 2e-5f && x.x > 0.213f && x.x < 0.343f && x.z > 0.227f && x.z < 0.332f;
    }
    EXPECT_EQ(onLight, 0);
}

} // namespace
} // namespace bounce
