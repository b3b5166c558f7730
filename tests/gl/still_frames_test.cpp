// Still frames converge (gl/renderer.h, Frame::accumulate, ShadowMaps::setStill): the frame's direct light
// averaged over still frames against closed forms that no part of Bounce computes.
//   - Soft shadow: a square emitter above a floor with a square occluder between them, parallel planes.
//     The irradiance at a floor point is the emitter's form factor less the part the occluder hides,
//     both axis-aligned rectangles in the emitter's plane, each by the corner formula of a differential
//     area under a parallel rectangle; the converged image along a row through umbra and penumbra
//     against it.
//   - Box-filtered pixels: an emitter whose edge runs through the centres of a column of pixels (a
//     viewport of odd width, not a power of two) reads half its radiance there, and its full radiance
//     or nothing one pixel either side.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/metrics.h"
#include "core/scene.h"
#include "gl/renderer.h"
#include "tests/form_factor.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class StillFramesTest : public GlTest {};

void addQuad(core::Scene& s, std::uint32_t material, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d)
{
    core::Mesh m;
    m.name = "quad" + std::to_string(s.meshes.size());
    m.material = material;
    const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    for (const glm::vec3& p : {a, b, c, d}) {
        m.positions.push_back(p);
        m.normals.push_back(n);
    }
    m.indices = {0, 1, 2, 0, 2, 3};
    s.meshes.push_back(m);
}

core::Material lambertian(const std::string& name, float rho, float emission = 0.0f)
{
    core::Material m;
    m.name = name;
    m.baseColor = glm::vec3(rho);
    m.specular = 0.0f;
    m.emission = glm::vec3(emission);
    return m;
}

// The soft-shadow case: floor y = 0 (albedo kRho), occluder [-kOcc, kOcc]^2 at y = kOccY, emitter
// [-kEmit, kEmit]^2 at y = kEmitY facing down with radiance kL. Camera between occluder and floor,
// looking straight down, so that image rows run along x.
constexpr float kRho = 0.5f, kL = 4.0f;
constexpr float kEmit = 0.25f, kEmitY = 1.0f, kOcc = 0.15f, kOccY = 0.5f;

core::Scene softShadowScene()
{
    core::Scene s;
    s.name = "soft-shadow";
    s.materials = {lambertian("floor", kRho), lambertian("occluder", 0.0f), lambertian("emitter", 0.0f, kL)};
    addQuad(s, 0, {-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}); // +y
    addQuad(s, 1, {-kOcc, kOccY, -kOcc}, {kOcc, kOccY, -kOcc}, {kOcc, kOccY, kOcc}, {-kOcc, kOccY, kOcc});
    addQuad(s, 2, {-kEmit, kEmitY, -kEmit}, {kEmit, kEmitY, -kEmit}, {kEmit, kEmitY, kEmit},
            {-kEmit, kEmitY, kEmit}); // -y: emits down
    s.camera.position = {0.0f, 0.3f, 0.0f};
    s.camera.forward = {0.0f, -1.0f, 0.0f};
    s.camera.up = {0.0f, 0.0f, 1.0f};
    s.camera.yfovRad = 2.0f * std::atan(0.65f / 0.3f); // the floor from x = -0.65 to 0.65
    s.camera.znear = 0.01f;
    s.camera.zfar = 10.0f;
    return s;
}

using testing::rectFormFactor;

// Reflected radiance rho L F_visible at floor point (x, z): the emitter's form factor less that of the
// occluder's shadow on the emitter's plane (the occluder seen from the point, scaled by kEmitY / kOccY).
double softShadowRadiance(double x, double z)
{
    const double e = kEmit, o = kOcc, k = double(kEmitY) / double(kOccY);
    const double full = rectFormFactor(-e - x, e - x, -e - z, e - z, kEmitY);
    // The occluder's edge at o seen from x meets the emitter's plane at k o + (1 - k) x.
    const double ox0 = std::max(-e, -k * o + (1.0 - k) * x), ox1 = std::min(e, k * o + (1.0 - k) * x);
    const double oz0 = std::max(-e, -k * o + (1.0 - k) * z), oz1 = std::min(e, k * o + (1.0 - k) * z);
    const double hidden = rectFormFactor(ox0 - x, ox1 - x, oz0 - z, oz1 - z, kEmitY);
    return kRho * kL * (full - hidden);
}

// The direct frame after `frames` frames of a still view.
core::Image stillImage(const core::Scene& scene, int w, int h, int frames, int shadowSize, bool accumulate = true,
                       const char* areaShadows = "hard", bool edgeAA = true)
{
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("shadow.size", shadowSize);
    frameValues.setValue("edgeAA", edgeAA ? 1 : 0);
    frameValues.setValue("accumulate", accumulate ? 1 : 0);
    frameValues.set(gl::frameParams(), "shadow.area", areaShadows);
    gl::Renderer r(scene, "direct", frameValues, gl::ParamValues(), w, h);
    for (int i = 0; i < frames; ++i) r.renderFrame(false);
    EXPECT_EQ(r.stillFrames(), accumulate ? frames - 1 : 0);
    return r.image();
}

// The analytic radiance of pixel (px, py) box-filtered over n x n points, as the path tracer's pixel is.
double boxFilteredSoftShadow(const core::Camera& c, int px, int py, int w, int h, int n = 4)
{
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const glm::vec3 d = c.rayDirection(float(px) + (float(i) + 0.5f) / float(n),
                                               float(py) + (float(j) + 0.5f) / float(n), w, h);
            const glm::vec3 p = c.position + d * (c.position.y / -d.y);
            sum += softShadowRadiance(p.x, p.z);
        }
    return sum / double(n * n);
}

// Measured (64x64, 512^2 cube faces): the largest difference along the row, as a share of the unshadowed
// radiance under the emitter's centre, 0.038 after 64 still frames, 0.018 after 128, 0.015 after 256 (the
// one-sample estimate's noise, falling); 0.45 for one frame (the polygon's exact form factor shadowed from
// the emitter's centre: a hard edge where the penumbra is).
constexpr double kSoftShadowTolerance = 0.03;
constexpr int kSoftShadowFrames = 256;

double softShadowRowError(const core::Image& img, const core::Scene& scene, int size, bool print)
{
    const int row = size / 2; // z near 0: the occluder's shadow spans the emitter's whole depth here
    const double unshadowed = kRho * kL * rectFormFactor(-kEmit, kEmit, -kEmit, kEmit, kEmitY); // under the centre
    double worst = 0.0;
    for (int x = 0; x < size; ++x) {
        const double want = boxFilteredSoftShadow(scene.camera, x, row, size, size);
        const double got = img.at(x, row).x;
        worst = std::max(worst, std::abs(got - want) / unshadowed);
        if (print && x % 4 == 0) std::printf("  x %2d: analytic %.4f, GL %.4f\n", x, want, got);
    }
    return worst;
}

TEST_F(StillFramesTest, AreaLightSoftShadowConvergesToTheClosedForm)
{
    const core::Scene scene = softShadowScene();
    constexpr int kSize = 64;
    // The row crosses the umbra (|x| < 0.05), both penumbrae and lit floor: all three are judged.
    ASSERT_LT(softShadowRadiance(0.0, 0.0), 1e-9);
    ASSERT_GT(softShadowRadiance(0.3, 0.0), 0.2 * softShadowRadiance(0.6, 0.0));
    const core::Image converged = stillImage(scene, kSize, kSize, kSoftShadowFrames, 512);
    const double error = softShadowRowError(converged, scene, kSize, true);
    std::printf("[ measured ] %d still frames: largest difference %.4g of the unshadowed radiance\n", kSoftShadowFrames,
                error);
    EXPECT_LT(error, kSoftShadowTolerance);
    // The negative control: without still frames the shadow is the centre's, hard, and clearly off.
    const double hard = softShadowRowError(stillImage(scene, kSize, kSize, 2, 512, false), scene, kSize, false);
    std::printf("[ measured ] one frame: %.4g\n", hard);
    EXPECT_GT(hard, 3.0 * kSoftShadowTolerance);
}

// The whole floor after 16 frames (the centroid and 15 sample points), relative RMSE against the closed
// form: the points must cover the emitter evenly already, not only in the limit. Measured (64x64, 512^2
// faces): 0.079 with the scrambled Sobol points (core::sobol2, seed 1; seeds 2 to 6: 0.057 to 0.071), 0.117
// with Halton's dimensions 2 and 3 (bases 5 and 7, whose first points lie on lines).
TEST_F(StillFramesTest, AreaLightPointsCoverTheEmitterEvenlyInSixteenFrames)
{
    const core::Scene scene = softShadowScene();
    constexpr int kSize = 64;
    core::Image closedForm(kSize, kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            closedForm.set(x, y, glm::vec3(float(boxFilteredSoftShadow(scene.camera, x, y, kSize, kSize))));
    const double error = core::relativeRmse(stillImage(scene, kSize, kSize, 16, 512), closedForm);
    std::printf("[ measured ] 16 frames: relative RMSE %.4g against the closed form\n", error);
    EXPECT_LT(error, 0.095);
}

// The moving frame's cheap option, percentage-closer soft shadows: closer to the closed form than the
// centroid's hard shadow, and lit floor (no blocker in reach) exactly as bright as without any shadow map
// (a blocker search that finds the receiver itself darkens it). Measured: largest difference 0.45 hard,
// 0.16 PCSS (an estimate: it also dims lit floor near the penumbra by up to 20%); the row's ends exact.
TEST_F(StillFramesTest, PcssSoftensTheMovingFrameAndLeavesLitFloorLit)
{
    const core::Scene scene = softShadowScene();
    constexpr int kSize = 64;
    const core::Image hard = stillImage(scene, kSize, kSize, 2, 512, false, "hard");
    const core::Image pcss = stillImage(scene, kSize, kSize, 2, 512, false, "pcss");
    const double hardError = softShadowRowError(hard, scene, kSize, false);
    const double pcssError = softShadowRowError(pcss, scene, kSize, true);
    std::printf("[ measured ] largest difference along the row: hard %.4g, PCSS %.4g\n", hardError, pcssError);
    EXPECT_LT(pcssError, 0.8 * hardError);
    // The row's ends (|x| > 0.6) see the whole emitter: no shadow at all.
    for (int x : {0, 1, kSize - 2, kSize - 1}) {
        const double want = boxFilteredSoftShadow(scene.camera, x, kSize / 2, kSize, kSize, 1);
        EXPECT_NEAR(pcss.at(x, kSize / 2).x, want, 0.01 * want) << "x " << x;
    }
}

// Moving frames only (accumulate off) with the reuse of their direct light: the emitters' ratio estimator.
gl::ParamValues ratioFrameValues(double alpha)
{
    gl::ParamValues v(gl::frameParams());
    v.setValue("accumulate", 0);
    v.setValue("temporal", 1);
    v.setValue("temporal.direct", 1);
    v.setValue("temporal.alpha", alpha);
    return v;
}

// A wall whose plane cuts the emitter with both of its triangles' centroids behind the wall (the emitter
// [-0.25, 0.25]^2 split along a diagonal, centroids at x = +-0.083; the wall at x = 0.1 facing +x sees the
// strip x > 0.1): the moving frame's exact form factor evaluates the BRDF towards the part of each triangle
// above the wall's horizon, not towards its centroid, below it, where the BRDF is 0 and the wall went black
// (cornell-area's tall block read 11% dark so). Against the still frames' mean, the unbiased point samples of
// the emitter (64 frames), on the wall's pixels. Measured: moving / still 0.98 (the centroid's form: 0).
TEST_F(StillFramesTest, MovingFrameLightsAWallThatSeesPartOfEachEmitterTriangle)
{
    core::Scene s;
    s.name = "wall-under-emitter";
    s.materials = {lambertian("wall", kRho), lambertian("emitter", 0.0f, kL)};
    addQuad(s, 0, {0.1f, 0, -1}, {0.1f, 0.9f, -1}, {0.1f, 0.9f, 1}, {0.1f, 0, 1}); // +x
    addQuad(s, 1, {-kEmit, kEmitY, -kEmit}, {kEmit, kEmitY, -kEmit}, {kEmit, kEmitY, kEmit},
            {-kEmit, kEmitY, kEmit}); // -y: emits down
    s.camera.position = {0.8f, 0.45f, 0.0f};
    s.camera.forward = {-1.0f, 0.0f, 0.0f};
    s.camera.up = {0.0f, 1.0f, 0.0f};
    s.camera.yfovRad = 1.0f;
    s.camera.znear = 0.01f;
    s.camera.zfar = 10.0f;
    constexpr int kSize = 32;
    // The moving frame's unshadowed light alone: with the ratio estimator (temporal.direct) and nothing
    // between wall and emitter, the visible share is 1. (The moving frame's own shadow, the cube at the
    // emitter's centre behind the wall, hides the wall from it.)
    gl::Renderer r(s, "direct", ratioFrameValues(0.2), gl::ParamValues(), kSize, kSize);
    r.renderFrame(false);
    ASSERT_TRUE(r.frame().areaRatioDrawn());
    const core::Image moving = r.image();
    const core::Image still = stillImage(s, kSize, kSize, 65, 256);
    double sumMoving = 0.0, sumStill = 0.0;
    for (int y = 4; y < kSize - 4; ++y) // the wall fills the view
        for (int x = 4; x < kSize - 4; ++x) {
            sumMoving += moving.at(x, y).x;
            sumStill += still.at(x, y).x;
        }
    std::printf("[ measured ] the wall, moving / still: %.4f (still mean %.4g)\n", sumMoving / sumStill,
                sumStill / ((kSize - 8) * (kSize - 8)));
    ASSERT_GT(sumStill, 0.0);
    EXPECT_NEAR(sumMoving / sumStill, 1.0, 0.03);
}

// Moving frames with the reuse of their direct light (`temporal.direct`): the emitters' light is the exact
// unshadowed light times the visible share, whose two sums the reuse averages (common/lighting.glsl,
// areaLightsRatio; Heitz et al. 2018). On a still view drawn as moving frames (the camera's pixel
// centres, no jitter):
//   - in the first frame already, floor that sees the whole emitter (the row's ends) holds the exact light:
//     only the visible share is sampled, and it is 1 there (mutation area-ratio-without-the-weight, which
//     resolves the mean of w V alone: half the light there).
//   - after 64 frames the row through umbra and penumbra is the closed form at the pixels' centres within
//     what 64 still frames reach (measured: 0.031 of the unshadowed radiance, against 0.038 for still frames).
TEST_F(StillFramesTest, MovingFramesRatioEstimatorIsExactWhereLitAndConvergesInThePenumbra)
{
    const core::Scene scene = softShadowScene();
    constexpr int kSize = 64;
    gl::Renderer r(scene, "direct", ratioFrameValues(0.01), gl::ParamValues(), kSize, kSize);
    r.renderFrame(false);
    ASSERT_TRUE(r.frame().areaRatioDrawn());
    ASSERT_EQ(r.frame().sampler().jitter(), glm::vec2(0.0f));
    core::Image first = r.image();
    for (int x : {0, 1, 2, kSize - 3, kSize - 2, kSize - 1}) {
        const double want = boxFilteredSoftShadow(scene.camera, x, kSize / 2, kSize, kSize, 1);
        EXPECT_NEAR(first.at(x, kSize / 2).x, want, 1e-3 * want) << "x " << x << ", the first frame";
    }
    for (int i = 1; i < 64; ++i) r.renderFrame(false);
    const int row = kSize / 2;
    const double unshadowed = kRho * kL * rectFormFactor(-kEmit, kEmit, -kEmit, kEmit, kEmitY);
    double worst = 0.0;
    for (int x = 0; x < kSize; ++x) {
        const double want = boxFilteredSoftShadow(scene.camera, x, row, kSize, kSize, 1);
        worst = std::max(worst, std::abs(r.image().at(x, row).x - want) / unshadowed);
    }
    std::printf("[ measured ] 64 moving frames: largest difference %.4g of the unshadowed radiance\n", worst);
    EXPECT_LT(worst, 0.04);
}

// An emitter (x <= 0 of the plane z = 0) seen head-on by a camera on the x = 0 line with an odd width:
// the middle column's pixel centres lie on the edge.
TEST_F(StillFramesTest, StillFramesAverageToBoxFilteredPixels)
{
    core::Scene s;
    s.name = "half-pixel";
    s.materials = {lambertian("emitter", 0.0f, 1.0f)};
    addQuad(s, 0, {-1, -1, 0}, {0, -1, 0}, {0, 1, 0}, {-1, 1, 0}); // +z: faces the camera
    s.camera.position = {0.0f, 0.0f, 1.0f};
    s.camera.forward = {0.0f, 0.0f, -1.0f};
    s.camera.up = {0.0f, 1.0f, 0.0f};
    s.camera.yfovRad = 0.5f;
    s.camera.znear = 0.01f;
    s.camera.zfar = 10.0f;
    constexpr int kW = 33, kH = 17, kFrames = 65; // 64 still frames
    const core::Image img = stillImage(s, kW, kH, kFrames, 64);
    for (int y = 0; y < kH; ++y) {
        EXPECT_NEAR(img.at(kW / 2, y).x, 0.5f, 0.04f) << "row " << y << ": the half-covered pixel";
        EXPECT_NEAR(img.at(kW / 2 - 1, y).x, 1.0f, 1e-5f) << "row " << y;
        EXPECT_NEAR(img.at(kW / 2 + 1, y).x, 0.0f, 1e-5f) << "row " << y;
    }
    std::printf("[ measured ] half-covered pixel after %d still frames: %.4f\n", kFrames - 1, img.at(kW / 2, 0).x);
    // Without them the pixel centre decides: all or nothing. The moving frames' edge antialiasing (edgeAA,
    // gl/frame/edge_antialias.h) gives the half-covered pixel its half from the first frame: one straight edge.
    const core::Image one = stillImage(s, kW, kH, 2, 64, false, "hard", false);
    EXPECT_TRUE(one.at(kW / 2, 0).x < 0.01f || one.at(kW / 2, 0).x > 0.99f);
    const core::Image antialiased = stillImage(s, kW, kH, 2, 64, false);
    for (int y = 0; y < kH; ++y) EXPECT_NEAR(antialiased.at(kW / 2, y).x, 0.5f, 0.01f) << "row " << y << ", edgeAA";
}

// A jittered frame rebuilds each pixel's position along the ray through its jittered sample, the very ray
// the G-buffer was rasterised with: on a floor seen at a slant every position stays on the floor. (Rebuilt
// along the pixel centre's ray with the jittered sample's depth, they leave it by up to ~1 mm here.)
TEST_F(StillFramesTest, JitteredFramesRebuildPositionsOnTheSurface)
{
    core::Scene scene = softShadowScene();
    scene.camera.position = {0.1f, 0.35f, -0.9f};
    scene.camera.forward = glm::normalize(glm::vec3(0.0f, 0.0f, 0.0f) - scene.camera.position);
    scene.camera.up =
        glm::normalize(glm::cross(glm::cross(scene.camera.forward, glm::vec3(0, 1, 0)), scene.camera.forward));
    scene.camera.yfovRad = 0.8f;
    gl::Renderer r(scene, "direct", gl::ParamValues(gl::frameParams()), gl::ParamValues(), 45, 31);
    for (int i = 0; i < 4; ++i) r.renderFrame(false);
    ASSERT_EQ(r.stillFrames(), 3);
    ASSERT_NE(r.frame().sampler().jitter(), glm::vec2(0.0f));
    const std::vector<float> pos = r.frame().readPositions();
    int floorPixels = 0;
    float worst = 0.0f;
    for (std::size_t i = 0; i < pos.size(); i += 4) {
        if (pos[i + 3] == 0.0f || std::abs(pos[i + 1]) > 0.05f) continue; // background, occluder, emitter
        ++floorPixels;
        worst = std::max(worst, std::abs(pos[i + 1]));
    }
    std::printf("[ measured ] %d floor pixels, farthest from the floor %.3g m\n", floorPixels, worst);
    EXPECT_GT(floorPixels, 45 * 31 / 3);
    EXPECT_LT(worst, 2e-5f);
}

// still.directSamples (Frame::renderDirectSubsamples): a still frame's direct light averaged over N points in
// the pixel, the frame's own and N - 1 more. Against the independent slower path, N times as many still
// frames of one point each: cornell-spot's direct light at 30x22 (not a power of two), 8 still frames of 4
// points against 128 of one, nearly as close as 32 frames of one, the same count of points (0.110 and 0.089
// measured: the further points are another sequence's, FrameSampler's DirectSubsample, and Halton's 32 in
// a row cover the pixel a little more evenly), where 8 frames of one are twice as far (0.231). The
// technique's G-buffer stays at the frame's own point: its positions are those of a frame of one point,
// to the bit.
TEST_F(StillFramesTest, DirectSamplesPerFrameConvergeAsThatManyFrames)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    constexpr int kW = 30, kH = 22;
    struct Run {
        core::Image image;
        std::vector<float> positions;
    };
    const auto still = [&](int samples, int stillFrames) {
        gl::ParamValues v(gl::frameParams());
        v.setValue("still.directSamples", samples);
        gl::Renderer r(scene, "direct", v, gl::ParamValues(), kW, kH);
        for (int i = 0; i <= stillFrames; ++i) r.renderFrame(false);
        EXPECT_EQ(r.stillFrames(), stillFrames);
        return Run{r.image(), r.frame().readPositions()};
    };
    const Run reference = still(1, 128), four = still(4, 8), sameCount = still(1, 32), one = still(1, 8);
    const double e4 = core::relativeRmse(four.image, reference.image);
    const double eSame = core::relativeRmse(sameCount.image, reference.image);
    const double e1 = core::relativeRmse(one.image, reference.image);
    std::printf("[ measured ] against 128 still frames: 8 of 4 points %.4f, 32 of one %.4f, 8 of one %.4f\n", e4, eSame,
                e1);
    EXPECT_LT(e4, 1.35 * eSame);
    EXPECT_GT(e1, 1.5 * e4) << "the case cannot tell the further points from none";
    EXPECT_EQ(four.positions, one.positions) << "the technique's G-buffer moved off the frame's own point";
}

} // namespace
} // namespace bounce
