// The RSM baselines and per-frame VPL clusters of image-space radiosity (gl/frame/rsm and gl/technique/isr/:
// vpl_sample, vpl_gather, isr_cluster) against closed forms: the gather of one VPL over a disk, the flux
// a spot, a point light and a directional light deliver to simple scenes, flux conservation through VPL
// sampling and clustering, the equality of the baselines at full sampling, and the hard cases of the
// issue (VPLs on receivers and in corners, a light that sees nothing, a light in a closed box, surfaces
// edge-on to the light, odd viewports, a point light 1 mm under the ceiling). Images are tiny: llvmpipe.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/image.h"
#include "core/metrics.h"
#include "gl/frame/frame.h"
#include "gl/frame/rsm.h"
#include "gl/renderer.h"
#include "gl/technique/isr/isr_cluster.h"
#include "gl/technique/isr/vpl_gather.h"
#include "gl/technique/isr/vpl_sample.h"
#include "tests/gl/cpu_raycast.h"
#include "tests/gl/gl_test_fixture.h"
#include "tests/image_expect.h"

namespace bounce {
namespace {

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------------
// Scenes built in code.

core::Material lambertian(const glm::vec3& albedo)
{
    core::Material m;
    m.baseColor = albedo;
    m.metallic = 0.0f;
    m.specular = 0.0f;
    m.roughness = 1.0f;
    return m;
}

// A flat polygon (a fan around its first vertex) whose triangles wind counter-clockwise seen from `n`.
core::Mesh polygon(const std::vector<glm::vec3>& v, const glm::vec3& n, std::uint32_t material)
{
    core::Mesh m;
    m.material = material;
    m.positions = v;
    m.normals.assign(v.size(), glm::normalize(n));
    for (std::uint32_t i = 1; i + 1 < v.size(); ++i) {
        const bool ccw = glm::dot(glm::cross(v[i] - v[0], v[i + 1] - v[0]), n) > 0.0f;
        m.indices.insert(m.indices.end(), {0u, ccw ? i : i + 1, ccw ? i + 1 : i});
    }
    return m;
}

// A horizontal square of half-size h at height y, facing +y (or -y).
core::Mesh square(float h, float y, bool up, std::uint32_t material)
{
    return polygon({{-h, y, -h}, {h, y, -h}, {h, y, h}, {-h, y, h}}, {0, up ? 1.0f : -1.0f, 0}, material);
}

core::Camera lookingDown(float height)
{
    core::Camera c;
    c.position = {0.0f, height, 0.0f};
    c.forward = {0.0f, -1.0f, 0.0f};
    c.up = {0.0f, 0.0f, 1.0f};
    c.yfovRad = float(kPi / 3.0);
    c.znear = 0.01f;
    c.zfar = 10.0f;
    return c;
}

core::Light spotDown(const glm::vec3& position, const glm::vec3& intensity, float coneRad)
{
    core::Light l;
    l.type = core::LightType::Spot;
    l.position = position;
    l.direction = {0.0f, -1.0f, 0.0f};
    l.intensity = intensity;
    l.innerConeRad = coneRad;
    l.outerConeRad = coneRad; // a hard cone
    return l;
}

gl::FrameSettings smallFrame(int w, int h)
{
    gl::FrameSettings s;
    s.width = w;
    s.height = h;
    s.shadowMapSize = 256;
    return s;
}

// ---------------------------------------------------------------------------------------------------
// Reading back.

struct GpuVpl {
    glm::vec4 positionArea, normal, flux;
};
static_assert(sizeof(GpuVpl) == gl::VplSampler::kVplBytes);

// Eq. 1 and 5 as glsl/technique/isr/vpl.glsl writes them, in double.
glm::dvec3 vplContributionCpu(const GpuVpl& v, const glm::dvec3& p, const glm::dvec3& n, const glm::dvec3& rho)
{
    const glm::dvec3 d = glm::dvec3(v.positionArea) - p;
    const double r2 = glm::dot(d, d), r = std::sqrt(r2);
    const glm::dvec3 w = r > 0.0 ? d / r : n;
    const double cosI = std::max(glm::dot(n, w), 0.0), cosJ = std::max(glm::dot(glm::dvec3(v.normal), -w), 0.0);
    return rho / kPi * glm::dvec3(v.flux) * (cosI * cosJ / (kPi * r2 + double(v.positionArea.w)));
}

// Sum of the reflected flux rho Phi over the level-0 texels of every view of the RSM.
glm::dvec3 rsmTotalFlux(const gl::RsmPass& rsm)
{
    const std::vector<float> f = rsm.flux().readFloats(0, 4);
    const int w = rsm.flux().width(), size = rsm.size();
    glm::dvec3 sum(0.0);
    for (int layer = 0; layer < rsm.viewCount(); ++layer)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const float* t = &f[((std::size_t(layer) * size + y) * w + x) * 4];
                sum += glm::dvec3(t[0], t[1], t[2]);
            }
    return sum;
}

glm::dvec3 vplTotalFlux(const gl::Buffer& cache, int count)
{
    std::vector<GpuVpl> v(std::size_t(std::max(count, 0)));
    cache.download(0, v.size() * sizeof(GpuVpl), v.data());
    glm::dvec3 sum(0.0);
    for (const GpuVpl& x : v) sum += glm::dvec3(x.flux);
    return sum;
}

void expectRelNear(const glm::dvec3& got, const glm::dvec3& want, double tol, const std::string& what)
{
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tol * std::abs(want[c])) << what << ", channel " << c;
}

// Every value finite; returns the largest.
float expectFinite(const core::Image& img, const std::string& what)
{
    float largest = 0.0f;
    std::size_t bad = 0;
    for (float v : img.rgb) {
        if (!std::isfinite(v))
            ++bad;
        else
            largest = std::max(largest, std::abs(v));
    }
    EXPECT_EQ(bad, 0u) << what << ": non-finite values";
    return largest;
}

struct Rendered {
    core::Image indirect, result;
    std::vector<gl::Counter> counters;
};

Rendered render(const core::Scene& scene, const std::string& technique,
                const std::vector<std::pair<std::string, std::string>>& sets, int w, int h)
{
    const gl::TechniqueInfo& info = gl::findTechnique(technique);
    gl::ParamValues frameValues(gl::frameParams()), values(info.params);
    frameValues.setValue("shadow.size", 256);
    for (const auto& [k, v] : sets) values.set(info.params, k, v);
    gl::Renderer r(scene, technique, frameValues, values, w, h);
    r.renderFrame();
    return {r.frame().read(r.frame().indirect()), r.image(), r.counters()};
}

double counter(const std::vector<gl::Counter>& cs, const std::string& name)
{
    for (const gl::Counter& c : cs)
        if (c.name == name) return c.value;
    ADD_FAILURE() << "no counter " << name;
    return 0.0;
}

class IsrRsmTest : public GlTest {};

// ---------------------------------------------------------------------------------------------------
// Eq. 1 / 5: one VPL above a disk.

// One VPL written straight into the cache, height h above a disk of radius R (facing it), gathered at
// every pixel. Per pixel: the gather equals Eqs. 1 and 5 evaluated in double on the CPU from the same
// G-buffer values (tolerance 1e-4 relative: float arithmetic). Over the disk: the integral of the
// outgoing radiance, sum_pixels L dA (dA = the pixel's footprint on the disk), equals the closed form
//   int L dA = rho_i/pi * rho_j Phi_j * pi h^2 / A_j * [ln(u / (pi u + A_j))]_{u = h^2}^{h^2 + R^2}
// (cos_i = cos_j = h/r, u = r^2). Tolerance 0.5%: rasterised disk edge at 128^2 (about 1e-3 of the
// integral, the disk's rim is dim), the 256-gon's area (1e-4), half-float albedo in the G-buffer (5e-4).
TEST_F(IsrRsmTest, SingleVplOverDiskMatchesDiskToPointIntegral)
{
    const double h = 0.5, R = 1.0, area = 0.05; // A_j large enough that the +A_j term matters (6%)
    const glm::vec3 rho(0.8f, 0.5f, 0.2f), flux(2.0f, 3.0f, 5.0f);
    core::Scene scene;
    scene.materials = {lambertian(rho)};
    std::vector<glm::vec3> rim;
    for (int i = 0; i < 256; ++i) {
        const double a = 2.0 * kPi * i / 256.0;
        rim.push_back({float(R * std::cos(a)), 0.0f, float(R * std::sin(a))});
    }
    scene.meshes = {polygon(rim, {0, 1, 0}, 0)};
    scene.camera = lookingDown(3.0f);

    constexpr int kSize = 128;
    gl::Frame frame(scene, smallFrame(kSize, kSize));
    gl::PassTimers timers;
    frame.beginFrame();
    frame.renderGBuffer(timers);
    frame.clearIndirect();
    const GpuVpl vpl{{0.0f, float(h), 0.0f, float(area)}, {0.0f, -1.0f, 0.0f, 0.0f}, {flux, 0.0f}};
    gl::Buffer cache("test.vpl", gl::vplCacheBytes(1));
    cache.update(0, sizeof vpl, &vpl);
    gl::VplGather gather;
    gather.gather(frame, cache, 1, timers);
    timers.endFrame(false);

    const std::vector<float> L = frame.indirect().readFloats(0, 4), P = frame.readPositions(), N = frame.readNormals(),
                             D = frame.diffuse().readFloats(0, 4);
    const core::Camera& cam = scene.camera;
    const double pixel = 2.0 * std::tan(0.5 * cam.yfovRad) / kSize; // pixel side on the image plane at distance 1
    glm::dvec3 integral(0.0);
    int covered = 0;
    for (int y = 0; y < kSize; ++y) // GL rows, bottom up
        for (int x = 0; x < kSize; ++x) {
            const std::size_t i = (std::size_t(y) * kSize + x) * 4;
            if (P[i + 3] == 0.0f) {
                ASSERT_EQ(L[i], 0.0f) << "background pixel " << x << "," << y;
                continue;
            }
            ++covered;
            const glm::dvec3 want = vplContributionCpu(vpl, {P[i], P[i + 1], P[i + 2]}, {N[i], N[i + 1], N[i + 2]},
                                                       {D[i], D[i + 1], D[i + 2]});
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(L[i + c], want[c], 1e-4 * want[c] + 1e-9) << "pixel " << x << "," << y << " channel " << c;
            const glm::dvec3 d(cam.rayDirection(x + 0.5f, float(kSize - 1 - y) + 0.5f, kSize, kSize));
            const double cosAxis = glm::dot(d, glm::dvec3(cam.forward)), cosPlane = -d.y;
            const double t = cam.position.y / cosPlane;
            const double dA = pixel * pixel * cosAxis * cosAxis * cosAxis * t * t / cosPlane;
            integral += glm::dvec3(L[i], L[i + 1], L[i + 2]) * dA;
        }
    EXPECT_GT(covered, 3000);
    const auto bracket = [&](double u) { return std::log(u / (kPi * u + area)); };
    const double geometric = kPi * h * h / area * (bracket(h * h + R * R) - bracket(h * h));
    const glm::dvec3 expected = glm::dvec3(rho) / kPi * glm::dvec3(flux) * geometric;
    expectRelNear(integral, expected, 5e-3, "integral of the gathered radiance over the disk");
}

// ---------------------------------------------------------------------------------------------------
// Flux in the RSM.

// A hard 45-degree spot 1 m above a 3 m x 3 m plane (which catches the whole cone): the RSM's total
// reflected flux is rho I Omega_cone, Omega_cone = 2 pi (1 - cos 45 deg) (closed form). With the exact
// per-texel solid angle the only error is which texels straddling the cone's rim count (Gauss's circle
// problem at 64^2: 0.2%), tolerance 1%; against the same sum computed on the CPU from the texels whose
// centre lies in the cone, 1e-4 (float sums). With Eq. 4 (every texel the same solid angle) the total is
// (texels in the cone) x Omega_frustum / size^2: the approximation's known bias, about -10.6% for a cone
// inscribed in a 90-degree map (pi^2/6 against 2 pi (1 - 1/sqrt 2) sr), checked to 1e-4.
TEST_F(IsrRsmTest, RsmTotalFluxMatchesSpotOnPlane)
{
    const glm::vec3 rho(0.5f, 0.25f, 0.75f), intensity(1.0f, 2.0f, 3.0f);
    const float cone = float(kPi / 4.0);
    core::Scene scene;
    scene.materials = {lambertian(rho)};
    scene.meshes = {square(1.5f, 0.0f, true, 0)};
    scene.lights = {spotDown({0.0f, 1.0f, 0.0f}, intensity, cone)};
    scene.camera = lookingDown(3.0f);
    constexpr int kRsm = 64;

    // The texels whose centre direction is inside the cone, and their exact and Eq. 4 solid angles.
    double exactInCone = 0.0;
    int inCone = 0;
    const double t = std::tan(double(cone));
    for (int y = 0; y < kRsm; ++y)
        for (int x = 0; x < kRsm; ++x) {
            const double u = t * (-1.0 + (2.0 * x + 1.0) / kRsm), v = t * (-1.0 + (2.0 * y + 1.0) / kRsm);
            if (1.0 / std::sqrt(1.0 + u * u + v * v) < std::cos(double(cone))) continue;
            ++inCone;
            exactInCone += gl::RsmPass::exactTexelSolidAngle(2.0 * cone, kRsm, x, y);
        }
    const glm::dvec3 rhoI = glm::dvec3(rho) * glm::dvec3(intensity);
    const glm::dvec3 closedForm = rhoI * (2.0 * kPi * (1.0 - std::cos(double(cone))));

    gl::Frame frame(scene, smallFrame(16, 16));
    for (bool exact : {true, false}) {
        gl::RsmSettings s;
        s.size = kRsm;
        s.exactSolidAngle = exact;
        gl::RsmPass rsm(s);
        gl::PassTimers timers;
        frame.beginFrame();
        rsm.render(frame, timers);
        timers.endFrame(false);
        ASSERT_EQ(rsm.viewCount(), 1);
        const glm::dvec3 total = rsmTotalFlux(rsm);
        if (exact) {
            expectRelNear(total, closedForm, 1e-2, "exact solid angles vs rho I 2 pi (1 - cos)");
            expectRelNear(total, rhoI * exactInCone, 1e-4, "exact solid angles vs the CPU texel sum");
        } else {
            const double eq4 = gl::RsmPass::equalTexelSolidAngle(2.0 * cone, kRsm);
            EXPECT_NEAR(eq4 * kRsm * kRsm, 2.0 * kPi / 3.0, 1e-6)
                << "a 90-degree frustum spans 4 pi / 6 sr (float cone)";
            expectRelNear(total, rhoI * (inCone * eq4), 1e-4, "Eq. 4 vs texels in cone x omega_frustum / size^2");
        }

        // Regular-grid sampling keeps the RSM's total: each VPL carries its whole block's flux.
        gl::VplSampler sampler;
        gl::Buffer cache("test.cache", 256 * gl::VplSampler::kVplBytes);
        const int n = sampler.sample(rsm, cache, gl::VplSampler::sideFor(256, 1, kRsm), timers);
        timers.endFrame(false);
        EXPECT_EQ(n, 256);
        expectRelNear(vplTotalFlux(cache, n), total, 1e-4, "256 regular-grid VPLs vs the RSM");
    }
}

// A point light inside a closed box: every direction meets a wall, so the cube RSM holds rho x 4 pi I,
// exactly for both solid-angle modes (six 90-degree faces sum to 4 pi sr either way); tolerance 1e-4.
// The indirect light inside is finite and positive everywhere.
TEST_F(IsrRsmTest, PointLightInsideClosedBox)
{
    const glm::vec3 rho(0.6f), intensity(1.0f, 0.5f, 0.25f);
    core::Scene scene;
    scene.materials = {lambertian(rho)};
    const float s = 1.0f;
    scene.meshes = {
        square(s, -s, true, 0),
        square(s, s, false, 0),
        polygon({{-s, -s, -s}, {-s, s, -s}, {-s, s, s}, {-s, -s, s}}, {1, 0, 0}, 0),
        polygon({{s, -s, -s}, {s, s, -s}, {s, s, s}, {s, -s, s}}, {-1, 0, 0}, 0),
        polygon({{-s, -s, -s}, {s, -s, -s}, {s, s, -s}, {-s, s, -s}}, {0, 0, 1}, 0),
        polygon({{-s, -s, s}, {s, -s, s}, {s, s, s}, {-s, s, s}}, {0, 0, -1}, 0),
    };
    core::Light point;
    point.type = core::LightType::Point;
    point.position = {0.1f, 0.2f, -0.1f};
    point.intensity = intensity;
    scene.lights = {point};
    scene.camera = lookingDown(0.9f);
    scene.camera.yfovRad = float(kPi / 2.0);

    gl::Frame frame(scene, smallFrame(16, 16));
    for (bool exact : {true, false}) {
        gl::RsmSettings rs;
        rs.size = 32;
        rs.exactSolidAngle = exact;
        gl::RsmPass rsm(rs);
        gl::PassTimers timers;
        frame.beginFrame();
        rsm.render(frame, timers);
        timers.endFrame(false);
        ASSERT_EQ(rsm.viewCount(), 6);
        expectRelNear(rsmTotalFlux(rsm), glm::dvec3(rho) * glm::dvec3(intensity) * (4.0 * kPi), 1e-4,
                      exact ? "exact solid angles" : "Eq. 4");
    }
    for (const char* technique : {"rsm", "isr"}) {
        const Rendered r = render(scene, technique, {{"rsmSize", "32"}}, 32, 32);
        expectFinite(r.indirect, technique);
        for (float v : r.indirect.rgb) ASSERT_GT(v, 0.0f) << technique << ": every wall sees lit walls";
    }
}

// A directional light straight down on a 2 m x 2 m plane: the orthographic RSM holds rho E A. Against
// the texels whose centre falls on the plane (CPU, same view as RsmPass builds) 1e-4; against the
// plane's true area 4% (its edges cut texels of 2 sqrt 2 / 64 m: the plane spans 45.25 texels per side,
// the 46 whose centres fall on it count, +3.3%).
TEST_F(IsrRsmTest, DirectionalLightFluxOnPlane)
{
    const glm::vec3 rho(0.5f), irradiance(2.0f, 1.0f, 3.0f);
    core::Scene scene;
    scene.materials = {lambertian(rho)};
    scene.meshes = {square(1.0f, 0.0f, true, 0)};
    core::Light sun;
    sun.type = core::LightType::Directional;
    sun.direction = {0.0f, -1.0f, 0.0f};
    sun.intensity = irradiance;
    scene.lights = {sun};
    scene.camera = lookingDown(3.0f);

    gl::Frame frame(scene, smallFrame(16, 16));
    gl::RsmSettings rs;
    rs.size = 64;
    gl::RsmPass rsm(rs);
    gl::PassTimers timers;
    frame.beginFrame();
    rsm.render(frame, timers);
    timers.endFrame(false);
    ASSERT_EQ(rsm.viewCount(), 1);
    const gl::LightView& v = rsm.views()[0];
    ASSERT_TRUE(v.orthographic);
    const glm::mat4 inv = glm::inverse(v.proj * v.view);
    int onPlane = 0;
    for (int y = 0; y < rs.size; ++y)
        for (int x = 0; x < rs.size; ++x) {
            const glm::vec4 ndc((2.0f * x + 1.0f) / rs.size - 1.0f, (2.0f * y + 1.0f) / rs.size - 1.0f, 0.0f, 1.0f);
            const glm::vec4 w = inv * ndc;
            if (std::abs(w.x / w.w) < 1.0f && std::abs(w.z / w.w) < 1.0f) ++onPlane;
        }
    const glm::dvec3 total = rsmTotalFlux(rsm), rhoE = glm::dvec3(rho) * glm::dvec3(irradiance);
    expectRelNear(total, rhoE * (double(onPlane) * rsm.orthoTexelArea(v)), 1e-4, "texels on the plane x texel area");
    expectRelNear(total, rhoE * 4.0, 4e-2, "rho E A");
}

// ---------------------------------------------------------------------------------------------------
// Sampling and clustering keep the flux; the baselines agree at full sampling.

// ISR's clusters partition the lit texels (each VPL its patch's summed flux), so the VPL cache holds the
// RSM's total flux for any thresholds (1e-4: float sums); VPL counts shrink as the thresholds grow.
TEST_F(IsrRsmTest, IsrClustersConserveFlux)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    gl::Frame frame(scene, smallFrame(16, 16));
    gl::RsmSettings rs;
    rs.size = 64;
    rs.levels = 4;
    gl::RsmPass rsm(rs);
    gl::PassTimers timers;
    frame.beginFrame();
    rsm.render(frame, timers);
    timers.endFrame(false);
    const glm::dvec3 total = rsmTotalFlux(rsm);
    ASSERT_GT(total.x, 0.0);

    gl::IsrCluster cluster;
    int previous = 1 << 30;
    for (float threshold : {0.0f, 0.05f, 0.5f, 1e6f}) {
        gl::IsrClusterSettings s;
        s.minLevel = 0;
        s.maxLevel = 4;
        s.depthThreshold = threshold;
        s.normalThreshold = threshold;
        gl::Buffer cache("test.cache", std::size_t(gl::IsrCluster::capacity(rsm, 0)) * gl::VplSampler::kVplBytes);
        const int n = cluster.cluster(rsm, cache, s, timers);
        timers.endFrame(false);
        expectRelNear(vplTotalFlux(cache, n), total, 1e-4, "threshold " + std::to_string(threshold));
        EXPECT_LE(n, previous) << "threshold " << threshold;
        int sum = 0;
        for (int c : cluster.perLevel()) sum += c;
        EXPECT_EQ(sum, n);
        previous = n;
    }
    EXPECT_LT(previous, 64 * 64 / 16) << "with no discontinuity test most patches are coarse";
}

// rsm with one VPL per RSM texel and rsm-full are the same computation; relative RMSE below 1e-3. Both
// share the RSM, the sampling and the gather kernel, so that equality alone would miss a gather that
// skips VPLs: the regular-grid pipeline (sampler and gather) is also checked against the sum over every
// lit texel of the RSM read back, on the CPU from the paper's equations (Eq. 3: A_j = omega_j |x_j -
// x_light|^2; Eqs. 1 and 5 in double), 1e-3 relative RMSE (float against double).
TEST_F(IsrRsmTest, RsmWithAllTexelsEqualsRsmFull)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    const Rendered full = render(scene, "rsm-full", {{"rsmSize", "32"}}, 32, 32);
    const Rendered grid = render(scene, "rsm", {{"rsmSize", "32"}, {"vpls", "1024"}}, 32, 32);
    EXPECT_EQ(counter(full.counters, "vpls"), 1024);
    EXPECT_EQ(counter(grid.counters, "vpls"), 1024);
    testing::expectImagesClose("rsm_all_texels_vs_rsm_full", grid.indirect, full.indirect,
                               testing::ImageMetric::relativeRmse(), 1e-3, "the same computation, float");

    constexpr int kSize = 32, kRsm = 32;
    gl::Frame frame(scene, smallFrame(kSize, kSize));
    gl::PassTimers timers;
    frame.beginFrame();
    frame.renderGBuffer(timers);
    frame.clearIndirect();
    gl::RsmSettings rs;
    rs.size = kRsm;
    gl::RsmPass rsm(rs);
    rsm.render(frame, timers);
    gl::VplSampler sampler;
    gl::Buffer cache("test.cache", gl::vplCacheBytes(kRsm * kRsm));
    const int count = sampler.sample(rsm, cache, kRsm, timers);
    gl::VplGather gather;
    gather.gather(frame, cache, count, timers);
    timers.endFrame(false);
    ASSERT_EQ(rsm.viewCount(), 1);
    ASSERT_FALSE(rsm.views()[0].orthographic);

    const std::vector<float> RP = rsm.position().readFloats(0, 4), RN = rsm.normal().readFloats(0, 4),
                             RF = rsm.flux().readFloats(0, 4);
    const glm::dvec3 origin(rsm.views()[0].origin);
    struct Texel {
        glm::dvec3 x, n, flux;
        double area;
    };
    std::vector<Texel> texels;
    for (std::size_t t = 0; t < std::size_t(kRsm) * kRsm; ++t) {
        const float* f = &RF[4 * t];
        if (std::max({f[0], f[1], f[2]}) <= 0.0f) continue;
        const glm::dvec3 x(RP[4 * t], RP[4 * t + 1], RP[4 * t + 2]);
        const double omega = f[3];
        texels.push_back({x, glm::dvec3(RN[4 * t], RN[4 * t + 1], RN[4 * t + 2]), glm::dvec3(f[0], f[1], f[2]),
                          std::max(omega * glm::dot(x - origin, x - origin), 1e-12)});
    }
    ASSERT_GT(texels.size(), std::size_t(kRsm * kRsm / 4)) << "the spot lights a good part of its RSM";
    const std::vector<float> P = frame.readPositions(), N = frame.readNormals(), D = frame.diffuse().readFloats(0, 4);
    core::Image want(kSize, kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const std::size_t i = (std::size_t(y) * kSize + x) * 4;
            if (P[i + 3] == 0.0f) continue;
            const glm::dvec3 p(P[i], P[i + 1], P[i + 2]), n(N[i], N[i + 1], N[i + 2]), rho(D[i], D[i + 1], D[i + 2]);
            glm::dvec3 sum(0.0);
            for (const Texel& t : texels) {
                const glm::dvec3 d = t.x - p;
                const double r2 = glm::dot(d, d);
                if (r2 <= 0.0) continue;
                const double cosI = std::max(glm::dot(n, d), 0.0) / std::sqrt(r2);
                const double cosJ = std::max(-glm::dot(t.n, d), 0.0) / std::sqrt(r2);
                sum += rho / kPi * t.flux * (cosI * cosJ / (kPi * r2 + t.area)); // Eqs. 1 and 5
            }
            want.set(x, kSize - 1 - y, glm::vec3(sum));
        }
    testing::expectImagesClose("rsm_grid_vs_cpu_sum_over_texels", frame.read(frame.indirect()), want,
                               testing::ImageMetric::relativeRmse(), 1e-3,
                               "float on the GPU against double on the CPU, the same texels");
}

// With both thresholds at 0 and the finest level at one texel, every lit texel is its own VPL, so isr
// gathers what rsm-full gathers (in another order); relative RMSE below 1e-3.
TEST_F(IsrRsmTest, IsrWithZeroThresholdsEqualsRsmFull)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    const Rendered full = render(scene, "rsm-full", {{"rsmSize", "32"}}, 32, 32);
    const Rendered isr = render(scene, "isr",
                                {{"rsmSize", "32"},
                                 {"lightDepthThreshold", "0"},
                                 {"lightNormalThreshold", "0"},
                                 {"minLevel", "0"},
                                 {"multires", "0"}},
                                32, 32);
    testing::expectImagesClose("isr_zero_thresholds_vs_rsm_full", isr.indirect, full.indirect,
                               testing::ImageMetric::relativeRmse(), 1e-3, "the same VPLs gathered in another order");
}

// ---------------------------------------------------------------------------------------------------
// Against ground truth.

// The onebounce-novis indirect light of cornell-spot computed on the CPU, independently of the GL path:
// every triangle is cut into small patches (about 1 cm), each gets its radiosity B = rho E from the spot
// (hard cone, inverse square, cosine, visibility by the CPU ray caster of tests/gl/cpu_raycast.h), and
// each pixel's surface point x (cast from the camera) gathers L = rho_x / pi sum B cos_x cos_y / (pi r^2) dA
// with no visibility between x and the patches, as the paper's Eq. 1 without the + A_j term.
core::Image cpuOneBounceNoVis(const core::Scene& scene, int size, double patch)
{
    struct Patch {
        glm::dvec3 p, n, radiosityTimesArea;
    };
    std::vector<Patch> patches;
    const core::Light& light = scene.lights.at(0);
    for (const core::Mesh& m : scene.meshes) {
        const glm::dvec3 rho(scene.materials[m.material].baseColor);
        for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]),
                c(m.positions[m.indices[t + 2]]);
            const glm::dvec3 cr = glm::cross(b - a, c - a);
            const double area = 0.5 * glm::length(cr);
            const glm::dvec3 n = cr / (2.0 * area);
            const int k = std::max(1, int(std::ceil(std::sqrt(area) / patch)));
            // k^2 sub-triangles of equal area: (i, j) upright and (i, j) inverted, sampled at their centroids.
            for (int i = 0; i < k; ++i)
                for (int j = 0; i + j < k; ++j)
                    for (int inverted = 0; inverted < (i + j + 1 < k ? 2 : 1); ++inverted) {
                        const double u = (i + (inverted ? 2.0 : 1.0) / 3.0) / k,
                                     v = (j + (inverted ? 2.0 : 1.0) / 3.0) / k;
                        const glm::dvec3 y = a + (b - a) * u + (c - a) * v;
                        const glm::dvec3 toLight = glm::dvec3(light.position) - y;
                        const double r2 = glm::dot(toLight, toLight);
                        const glm::dvec3 wi = toLight / std::sqrt(r2);
                        const double cosY = glm::dot(n, wi);
                        if (cosY <= 0.0 ||
                            glm::dot(-wi, glm::dvec3(light.direction)) < std::cos(double(light.outerConeRad)))
                            continue;
                        if (!test::visible(scene, glm::vec3(y), glm::vec3(n), light.position)) continue;
                        patches.push_back({y, n, rho * glm::dvec3(light.intensity) * (cosY / r2) * (area / (k * k))});
                    }
        }
    }
    core::Image img(size, size);
    for (int py = 0; py < size; ++py)
        for (int px = 0; px < size; ++px) {
            const glm::vec3 d = scene.camera.rayDirection(px + 0.5f, py + 0.5f, size, size);
            const auto hit = test::raycast(scene, scene.camera.position, d);
            if (!hit || glm::dot(hit->geometricNormal, d) >= 0.0f) continue; // background or a back face
            const glm::dvec3 x(hit->position), nx(hit->geometricNormal);
            glm::dvec3 sum(0.0);
            for (const Patch& q : patches) {
                const glm::dvec3 v = q.p - x;
                const double r2 = glm::dot(v, v);
                const glm::dvec3 w = v / std::sqrt(r2);
                const double cosX = glm::dot(nx, w), cosY = -glm::dot(q.n, w);
                if (cosX > 0.0 && cosY > 0.0) sum += q.radiosityTimesArea * (cosX * cosY / (kPi * r2));
            }
            img.set(px, py, glm::vec3(glm::dvec3(scene.materials[hit->material].baseColor) / kPi * sum));
        }
    return img;
}

// rsm-full (a 64^2 RSM with exact texel solid angles: 4096 VPLs) against the CPU ground truth of the same
// light paths at 32 x 32. Tolerance 10% relative RMSE (measured: 7.9% on llvmpipe) and 3% on the mean
// (measured: 1.2%): both sides discretise the lit surfaces (RSM texels of about 1.7 cm on the floor, CPU
// patches of 1 cm) and both are singular where a receiver meets a lit surface (the blocks' feet, the
// box's corners), where the + A_j term of Eq. 1 and the different sample positions part them by 10-20%
// over a few pixels; away from those pixels they agree to about 1%. The
// project's path tracer (ref/, light paths onebounce-novis-indirect) is not linked into gl_tests, and
// `bounce reference` is not available yet: this CPU quadrature stands in for it.
TEST_F(IsrRsmTest, RsmFullMatchesCpuOneBounceNoVis)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    constexpr int kSize = 32;
    const core::Image truth = cpuOneBounceNoVis(scene, kSize, 0.01);
    const Rendered full = render(scene, "rsm-full", {{"rsmSize", "64"}, {"exactSolidAngle", "1"}}, kSize, kSize);
    const core::ImageMetrics m = core::compareImages(full.indirect, truth);
    testing::expectImagesClose("rsm_full_vs_cpu", full.indirect, truth, testing::ImageMetric::relativeRmse(), 0.10,
                               "RSM texels against CPU patches; both singular where receivers meet lit surfaces");
    testing::expectImagesClose("rsm_full_vs_cpu_mean", full.indirect, truth, testing::ImageMetric::meanRelative(), 0.03,
                               "the bounce's overall energy");
    // The paper's Eq. 4 (every texel the same solid angle) gives the texels under the spot half their
    // solid angle (a 90-degree map's centre texel spans 1.9 x the mean): reported, not asserted.
    const Rendered eq4 = render(scene, "rsm-full", {{"rsmSize", "64"}}, kSize, kSize);
    const core::ImageMetrics e = core::compareImages(eq4.indirect, truth);
    std::printf("rsm-full (64^2 RSM) vs CPU onebounce-novis indirect, relative RMSE: exact solid angles %.4f "
                "(mean %.3f of the truth's), Eq. 4 %.4f (mean %.3f)\n",
                m.relativeRmse, m.meanImage / m.meanReference, e.relativeRmse, e.meanImage / e.meanReference);
}

// ---------------------------------------------------------------------------------------------------
// Hard cases.

// VPLs on the receiver itself and in the corners where walls meet, written straight into the cache of
// cornell-spot's G-buffer with a tiny area (1e-8 m^2): the + A_j term keeps every pixel finite and
// below its bound rho/pi * rho_j Phi_j / A_j, and a VPL in the plane of its receiver adds nothing there.
TEST_F(IsrRsmTest, VplsOnReceiverAndInCornersStayFinite)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    constexpr int kSize = 32;
    gl::Frame frame(scene, smallFrame(kSize, kSize));
    gl::PassTimers timers;
    frame.beginFrame();
    frame.renderGBuffer(timers);
    frame.clearIndirect();
    const std::vector<float> P = frame.readPositions(), N = frame.readNormals();
    const std::size_t centre = (std::size_t(kSize / 2) * kSize + kSize / 2) * 4;
    ASSERT_EQ(P[centre + 3], 1.0f);
    const float area = 1e-8f;
    const glm::vec4 flux(1.0f, 1.0f, 1.0f, 0.0f);
    std::vector<GpuVpl> vpls = {
        {{P[centre], P[centre + 1], P[centre + 2], area}, {N[centre], N[centre + 1], N[centre + 2], 0}, flux},
        {{0.0f, 0.0f, 0.0f, area}, {0, 1, 0, 0}, flux},        // floor / right wall / front corner
        {{0.0f, 0.0f, 0.5592f, area}, {1, 0, 0, 0}, flux},     // right wall at the floor and back wall
        {{0.5496f, 0.0f, 0.5592f, area}, {0, 0, -1, 0}, flux}, // back wall at the floor and left wall
        {{0.0f, 0.5488f, 0.5592f, area}, {0, -1, 0, 0}, flux}, // ceiling corner
        {{0.2f, 0.0f, 0.5592f, area}, {0, 1, 0, 0}, flux},     // floor along the back wall
    };
    gl::Buffer cache("test.vpl", gl::vplCacheBytes(int(vpls.size())));
    cache.update(0, vpls.size() * sizeof(GpuVpl), vpls.data());
    gl::VplGather gather;
    gather.gather(frame, cache, int(vpls.size()), timers);
    timers.endFrame(false);
    const core::Image img = frame.read(frame.indirect());
    const float largest = expectFinite(img, "indirect");
    EXPECT_LE(largest, float(vpls.size()) * 1.0f / float(kPi) / area);
    EXPECT_GT(largest, 0.0f);

    // The receiver's own VPL alone: nothing at its own pixel (cos_j = 0 in its plane), finite elsewhere.
    gl::Buffer own("test.vpl.own", gl::vplCacheBytes(1));
    own.update(0, sizeof(GpuVpl), vpls.data());
    frame.clearIndirect();
    gather.gather(frame, own, 1, timers);
    timers.endFrame(false);
    const std::vector<float> L = frame.indirect().readFloats(0, 4);
    EXPECT_EQ(L[centre], 0.0f);
    expectFinite(frame.read(frame.indirect()), "receiver's own VPL");
}

// Every RSM texel a VPL on cornell-spot, including those at the corners where walls meet the floor:
// finite output, and no pixel's indirect light above 10 x the brightest direct light (one diffuse bounce
// in a box of albedo below 0.75 is far dimmer; an unbounded 1/r^2 at a corner would break this).
TEST_F(IsrRsmTest, CornellCornersFiniteAndBounded)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    for (const char* technique : {"rsm-full", "isr"}) {
        const Rendered r = render(scene, technique, {{"rsmSize", "64"}}, 32, 32);
        const float indirect = expectFinite(r.indirect, technique);
        expectFinite(r.result, technique);
        float direct = 0.0f;
        for (std::size_t i = 0; i < r.result.rgb.size(); ++i)
            direct = std::max(direct, r.result.rgb[i] - r.indirect.rgb[i]);
        EXPECT_GT(indirect, 0.0f) << technique;
        EXPECT_LT(indirect, 10.0f * direct) << technique;
    }
}

// A spot above the box pointing up into nothing: the RSM sees no geometry; zero indirect, no NaN.
TEST_F(IsrRsmTest, LightThatSeesNothingGivesZero)
{
    core::Scene scene = core::makeCornell("cornell-spot");
    scene.lights[0].position = {0.278f, 3.0f, 0.2795f};
    scene.lights[0].direction = {0.0f, 1.0f, 0.0f};
    for (const char* technique : {"rsm", "rsm-full", "isr"}) {
        const Rendered r = render(scene, technique, {{"rsmSize", "32"}}, 16, 16);
        EXPECT_EQ(expectFinite(r.indirect, technique), 0.0f) << technique;
        if (std::string(technique) == "isr") {
            EXPECT_EQ(counter(r.counters, "vpls"), 0.0);
        }
    }
}

// A spot lying in the plane of the floor, shining along it onto a wall: the floor is exactly edge-on to
// the light (no RSM texel on it). The wall's bounce still lights the floor; everything stays finite.
TEST_F(IsrRsmTest, SurfaceEdgeOnToLight)
{
    core::Scene scene;
    scene.materials = {lambertian(glm::vec3(0.7f))};
    scene.meshes = {square(1.0f, 0.0f, true, 0),
                    polygon({{1, 0, -1}, {1, 1, -1}, {1, 1, 1}, {1, 0, 1}}, {-1, 0, 0}, 0)};
    core::Light spot = spotDown({-0.5f, 0.0f, 0.0f}, glm::vec3(1.0f), float(kPi / 4.0));
    spot.direction = {1.0f, 0.0f, 0.0f};
    scene.lights = {spot};
    scene.camera = lookingDown(3.0f);
    for (const char* technique : {"rsm", "rsm-full", "isr"}) {
        const Rendered r = render(scene, technique, {{"rsmSize", "32"}}, 32, 32);
        EXPECT_GT(expectFinite(r.indirect, technique), 0.0f) << technique;
    }
}

// Viewports that are not multiples of the 8 x 8 gather tile, and a single pixel: no out-of-range access
// (GL errors fail the fixture), no NaN, and indirect light where there must be some.
TEST_F(IsrRsmTest, OddViewports)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    for (const char* technique : {"rsm", "isr"}) {
        const Rendered wide = render(scene, technique, {{"rsmSize", "32"}}, 333, 200);
        EXPECT_GT(expectFinite(wide.indirect, technique), 0.0f) << technique;
        const Rendered one = render(scene, technique, {{"rsmSize", "32"}}, 1, 1);
        EXPECT_GT(expectFinite(one.indirect, technique), 0.0f) << technique << ": the centre pixel sees the tall block";
    }
}

// The hard variant: the point light 1 mm under the ceiling. The ceiling's RSM texels around it have tiny
// areas (Eq. 3: omega |V|^2 with |V| about 1 mm) but finite flux; everything stays finite.
TEST_F(IsrRsmTest, PointLightUnderCeilingFinite)
{
    const core::Scene scene = core::makeCornell("cornell-point-ceiling");
    for (const char* technique : {"rsm", "rsm-full", "isr"}) {
        const Rendered r = render(scene, technique, {{"rsmSize", "32"}}, 32, 32);
        EXPECT_GT(expectFinite(r.indirect, technique), 0.0f) << technique;
        expectFinite(r.result, technique);
    }
}

// The area light of cornell-area as a cosine-lobe emitter: the RSM holds rho x the flux the emitter
// sends into the room. Its intensity L A cos(theta) integrates to pi L A over the lower hemisphere; the
// box's walls, floor and blocks catch all of it except what leaves through the open front (the camera
// side). Checked loosely (the hemisphere's flux times the albedos lies between 0.05 and 0.75 of pi L A
// per channel) and finite everywhere.
TEST_F(IsrRsmTest, AreaLightAsCosineEmitter)
{
    const core::Scene scene = core::makeCornell("cornell-area");
    gl::Frame frame(scene, smallFrame(16, 16));
    gl::RsmSettings rs;
    rs.size = 32;
    gl::RsmPass rsm(rs);
    gl::PassTimers timers;
    frame.beginFrame();
    rsm.render(frame, timers);
    timers.endFrame(false);
    ASSERT_EQ(rsm.viewCount(), 6);
    const glm::dvec3 emitted = glm::dvec3(17.0, 12.0, 4.0) * (0.13 * 0.105) * kPi;
    const glm::dvec3 total = rsmTotalFlux(rsm);
    for (int c = 0; c < 3; ++c) {
        EXPECT_GT(total[c], 0.05 * emitted[c]) << c;
        EXPECT_LT(total[c], 0.75 * emitted[c]) << c;
    }
    const Rendered r = render(scene, "rsm", {{"rsmSize", "32"}}, 16, 16);
    EXPECT_GT(expectFinite(r.indirect, "rsm on cornell-area"), 0.0f);
}

} // namespace
} // namespace bounce
