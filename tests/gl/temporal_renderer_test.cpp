// Temporal reuse in the Renderer (frame parameter `temporal`, gl/renderer.h): a technique that declares
// TechniqueInfo::temporalReuse draws new samples every moving frame and blends them with its reprojected
// history; one that does not renders as without the parameter. The pass itself is checked in
// temporal_reuse_test.cpp against closed forms (exact reprojection, disocclusion, clamp).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/image.h"
#include "core/metrics.h"
#include "gl/renderer.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class TemporalRendererTest : public GlTest {};

constexpr int kW = 40, kH = 28;

// Moving frames (accumulate off: no still mean), small shadow maps; temporal reuse on or off.
gl::ParamValues frameValues(bool temporal, double alpha = 0.2)
{
    gl::ParamValues v(gl::frameParams());
    v.setValue("shadow.size", 256);
    v.setValue("accumulate", 0);
    v.setValue("temporal", temporal ? 1 : 0);
    v.setValue("temporal.alpha", alpha);
    return v;
}

gl::ParamValues photonValues()
{
    gl::ParamValues v(gl::findTechnique("photon").params);
    v.setValue("photons", 4096);
    v.setValue("clusters", 64);
    v.setValue("gatherRays", 16);
    return v;
}

// The root mean square change of the indirect light from one frame to the next, relative to its mean:
// what the viewer sees as flicker on a still view.
double relativeChange(const core::Image& a, const core::Image& b)
{
    double sq = 0.0, sum = 0.0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const double d = double(a.at(x, y)[c]) - double(b.at(x, y)[c]);
                sq += d * d;
                sum += b.at(x, y)[c];
            }
    const double n = 3.0 * a.width * a.height;
    return std::sqrt(sq / n) / std::max(sum / n, 1e-30);
}

// Two frames' indirect light after `warmup` frames of the same view.
std::pair<core::Image, core::Image> lastTwo(gl::Renderer& r, int warmup)
{
    for (int i = 0; i < warmup; ++i) r.renderFrame(false);
    r.renderFrame(false);
    const core::Image a = r.frame().read(r.frame().indirect());
    r.renderFrame(false);
    return {a, r.frame().read(r.frame().indirect())};
}

// Without temporal reuse a moving frame draws the same photons every frame (its image stays what it was);
// with it each frame draws new ones (alpha 1: no history kept, the raw frames) and the reuse averages
// them: the frame-to-frame change falls to a fraction. An EMA of weight alpha over independent frames
// leaves sqrt(alpha / (2 - alpha)) of their change between consecutive outputs: 0.33 at alpha 0.2, before
// the clamp lets some of it back (the 3x3 neighbourhood of one noisy frame spans most of the noise).
// Measured here (40x28, photon's quickSets): raw 0.77, reused 0.36 (0.47 of it). Bound: under 0.75 of
// the raw change. Without the reuse pass it is the raw change; with moving frames that repeat their seed
// the raw change is 0.
TEST_F(TemporalRendererTest, PhotonDrawsNewSamplesAndTheReuseAveragesThem)
{
    const core::Scene scene = core::makeCornell("cornell-area");
    gl::Renderer off(scene, "photon", frameValues(false), photonValues(), kW, kH);
    const auto [offA, offB] = lastTwo(off, 1);
    EXPECT_EQ(relativeChange(offA, offB), 0.0) << "without temporal reuse a moving frame repeats its samples";

    gl::Renderer raw(scene, "photon", frameValues(true, 1.0), photonValues(), kW, kH);
    const auto [rawA, rawB] = lastTwo(raw, 1);
    const double rawChange = relativeChange(rawA, rawB);
    EXPECT_GT(rawChange, 0.02) << "under temporal reuse each moving frame draws new samples";

    gl::Renderer reused(scene, "photon", frameValues(true, 0.2), photonValues(), kW, kH);
    const auto [a, b] = lastTwo(reused, 10);
    const double change = relativeChange(a, b);
    std::printf("[ temporal ] photon: frame-to-frame change %.3f raw, %.3f with reuse (alpha 0.2)\n", rawChange,
                change);
    EXPECT_LT(change, 0.75 * rawChange) << "the reuse does not average the frames";
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(b.at(x, y)[c]) && b.at(x, y)[c] >= 0.0f);
}

// A technique that does not declare temporal reuse renders the same images with the parameter on.
TEST_F(TemporalRendererTest, UndeclaredTechniqueIsUntouched)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    gl::ParamValues rsm(gl::findTechnique("rsm").params);
    rsm.setValue("vpls", 64);
    gl::Renderer on(scene, "rsm", frameValues(true), rsm, kW, kH), off(scene, "rsm", frameValues(false), rsm, kW, kH);
    ASSERT_FALSE(on.temporalReuse());
    for (int i = 0; i < 3; ++i) {
        on.renderFrame(false);
        off.renderFrame(false);
    }
    EXPECT_EQ(relativeChange(on.image(), off.image()), 0.0);
}

} // namespace
} // namespace bounce

namespace bounce {
namespace {

// temporal.direct on a still view drawn as moving frames (accumulate off), in a scene without emitting
// triangles (cornell-point), whose whole direct light the reuse blends (with emitters only their visible
// share is: still_frames_test.cpp, MovingFramesRatioEstimator...). Moving frames sample the pixels' centres
// and a point light's shadow is exact in the still form they take, so every frame is the same image and the
// reuse must give it back exactly, 16 frames on (a history resampled a fraction of a pixel off, the snap
// of temporal_reuse.frag undone, blurs it). Against an independent path, the still frames' mean (frames
// 1..16, jittered): equal on 4x4-pixel blocks that lie on one plane (one normal, one offset along it),
// the blocks compared here (silhouettes and creases left out, where a still frame's jitter box-filters an
// edge that a pixel centre does not). Within 3% (measured: 2.05% over 120 blocks, the shadows' edges).
TEST_F(TemporalRendererTest, DirectLightReuseOfAStillViewIsTheMeanOfTheStillFramesOnEachPlane)
{
    const core::Scene scene = core::makeCornell("cornell-point");
    const gl::ParamValues t(gl::findTechnique("direct").params);
    gl::ParamValues moving = frameValues(true, 0.01), still = frameValues(false);
    moving.setValue("temporal.direct", 1);
    still.setValue("accumulate", 1);
    gl::Renderer reused(scene, "direct", moving, t, 64, 64), accumulated(scene, "direct", still, t, 64, 64);
    accumulated.renderFrame(false);
    core::Image first;
    for (int k = 1; k <= 16; ++k) {
        reused.renderFrame(false);
        accumulated.renderFrame(false);
        if (k == 1) first = reused.image();
        ASSERT_EQ(reused.frame().sampler().sampleIndex(), accumulated.frame().sampler().stillIndex());
        ASSERT_EQ(reused.frame().sampler().jitter(), glm::vec2(0.0f)) << "a moving frame samples pixel centres";
    }
    EXPECT_EQ(relativeChange(reused.image(), first), 0.0) << "the reuse of identical frames changed them";
    // Blocks on one plane: every pixel sees geometry with the block's first normal and lies on its plane.
    const std::vector<float> p = reused.frame().readPositions(), n = reused.frame().readNormals(); // GL rows
    const auto onOnePlane = [&](int bx, int by) {
        const auto at = [](int x, int y) { return (std::size_t(63 - y) * 64 + std::size_t(x)) * 4; };
        const std::size_t o = at(bx * 4, by * 4);
        const glm::vec3 p0(p[o], p[o + 1], p[o + 2]), n0(n[o], n[o + 1], n[o + 2]);
        for (int y = by * 4; y < by * 4 + 4; ++y)
            for (int x = bx * 4; x < bx * 4 + 4; ++x) {
                const std::size_t i = at(x, y);
                const glm::vec3 pi(p[i], p[i + 1], p[i + 2]), ni(n[i], n[i + 1], n[i + 2]);
                if (p[i + 3] == 0.0f || glm::dot(ni, n0) < 0.999f || std::abs(glm::dot(n0, pi - p0)) > 1e-3f)
                    return false;
            }
        return true;
    };
    const core::Image a = core::boxDownsample(reused.image(), 16, 16);
    const core::Image b = core::boxDownsample(accumulated.image(), 16, 16);
    double se = 0.0, sum = 0.0;
    int blocks = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const glm::vec3 u = a.at(x, y), v = b.at(x, y);
            if (std::max({v.x, v.y, v.z}) > 1.0f || !onOnePlane(x, y)) continue;
            ++blocks;
            se += glm::dot(u - v, u - v);
            sum += v.x + v.y + v.z;
        }
    const double relative = std::sqrt(se / (blocks * 3.0)) / (sum / (blocks * 3.0));
    std::printf("[ measured ] reused moving frames against the still mean, %d 4x4 blocks on one plane: %.4f\n", blocks,
                relative);
    EXPECT_GE(blocks, 100);
    EXPECT_LT(relative, 0.03);
}

// A moving camera over a point light's shadows (cornell-point): every moving frame's direct light is exact
// at its pixels' centres (shadow rays), so the reuse only antialiases, and its history is clamped to the
// current frame's 3x3 neighbourhood as temporal antialiasing clamps it. Against an independent path, a
// fresh renderer at the last camera, whose one frame is that frame's own light: after 16 frames along a
// sideways move of about half a pixel a frame, every pixel lies within its 3x3 neighbourhood there (to
// float rounding). Unclamped, the history resampled every frame trails the moving silhouettes and shadow
// edges (measured: 1,015 of the 12,288 values outside, by up to 0.126 where the lit floor reads 0.204).
TEST_F(TemporalRendererTest, DirectLightReuseOfPunctualLightsStaysWithinTheCurrentNeighbourhood)
{
    const core::Scene scene = core::makeCornell("cornell-point");
    const gl::ParamValues t(gl::findTechnique("direct").params);
    gl::ParamValues v = frameValues(true, 0.1);
    v.setValue("temporal.direct", 1);
    gl::Renderer moving(scene, "direct", v, t, 64, 64);
    core::Camera camera = scene.camera;
    for (int k = 0; k < 16; ++k) {
        camera.position.x += 0.0075f; // about half a pixel at the back wall
        moving.frame().setCamera(camera);
        moving.renderFrame(false);
    }
    gl::Renderer fresh(scene, "direct", v, t, 64, 64);
    fresh.frame().setCamera(camera);
    fresh.renderFrame(false);
    const core::Image a = moving.image(), c = fresh.image();
    int outside = 0;
    float worst = 0.0f;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            for (int ch = 0; ch < 3; ++ch) {
                float lo = INFINITY, hi = -INFINITY;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const float n = c.at(std::clamp(x + dx, 0, 63), std::clamp(y + dy, 0, 63))[ch];
                        lo = std::min(lo, n);
                        hi = std::max(hi, n);
                    }
                const float u = a.at(x, y)[ch], slack = 1e-5f * std::max(hi, 1.0f);
                if (u < lo - slack || u > hi + slack) {
                    ++outside;
                    worst = std::max(worst, std::max(lo - u, u - hi));
                }
            }
    const float floorLight = c.at(32, 60).x;
    std::printf("[ measured ] values outside the current 3x3 neighbourhood: %d of %d, worst %.3g (floor %.3g)\n",
                outside, 64 * 64 * 3, worst, floorLight);
    EXPECT_EQ(outside, 0);
    EXPECT_GT(relativeChange(a, c), 0.0) << "the history took no part: the test saw no reuse";
}

// moving.directSamples (Frame::renderDirectSubsamples in a moving frame): the moving frame's direct light
// averaged over N points in the pixel, its centre and N - 1 more, antialiases what the pixel centres alone
// alias (shadow edges, silhouettes). cornell-point's moving frames (with temporal.direct their shadows are
// rays, exact at each point; alpha 1: no history), 30x22 (not a power of two), against an independent path:
// 256 still frames of one point each, the box-filtered pixels. One moving frame of 16 points lies far closer
// to it than one of the centres alone (measured: 0.0467 against 0.2838). The technique's G-buffer stays at
// the pixel centres, to the bit.
TEST_F(TemporalRendererTest, MovingDirectSamplesAntialiasTheMovingFrame)
{
    const core::Scene scene = core::makeCornell("cornell-point");
    constexpr int kSmallW = 30, kSmallH = 22;
    const gl::ParamValues t(gl::findTechnique("direct").params);
    struct Run {
        core::Image image;
        std::vector<float> positions;
    };
    const auto moving = [&](int samples) {
        gl::ParamValues v = frameValues(true, 1.0);
        v.setValue("temporal.direct", 1);
        v.setValue("moving.directSamples", samples);
        gl::Renderer r(scene, "direct", v, t, kSmallW, kSmallH);
        r.renderFrame(false);
        r.renderFrame(false);
        EXPECT_EQ(r.frame().sampler().stillIndex(), 0);
        EXPECT_EQ(r.frame().sampler().jitter(), glm::vec2(0.0f)) << "the frame's own point left the pixel centre";
        return Run{r.image(), r.frame().readPositions()};
    };
    gl::ParamValues s = frameValues(false);
    s.setValue("accumulate", 1);
    gl::Renderer still(scene, "direct", s, t, kSmallW, kSmallH);
    for (int i = 0; i <= 256; ++i) still.renderFrame(false);
    ASSERT_EQ(still.stillFrames(), 256);
    const Run sixteen = moving(16), one = moving(1);
    const double e16 = core::relativeRmse(sixteen.image, still.image());
    const double e1 = core::relativeRmse(one.image, still.image());
    std::printf("[ measured ] one moving frame against 256 still frames: 16 points %.4f, the centres alone %.4f\n", e16,
                e1);
    EXPECT_LT(e16, 0.5 * e1);
    EXPECT_EQ(sixteen.positions, one.positions) << "the technique's G-buffer moved off the pixel centres";
}

// The frame's shadow pass draws only what a pass reads (Frame::setShadowMapsRead): `direct` reads no map
// of its own, and its still form with shadow rays (still frames; moving frames with the reuse of the direct
// light) reads none either, so those frames draw none; its moving form reads the emitter's cube, and a
// technique that does not say otherwise (photon) keeps every map in every frame. The images these frames
// make are checked elsewhere against closed forms (StillFramesTest: the ratio estimator, the soft shadow).
TEST_F(TemporalRendererTest, ShadowPassDrawsOnlyWhatSomethingReads)
{
    const core::Scene scene = core::makeCornell("cornell-area");
    const auto texels = [](const gl::Renderer& r) {
        for (const gl::Counter& c : r.frameCounters())
            if (c.name == "shadow.texels") return c.value;
        return -1.0;
    };
    const gl::ParamValues direct(gl::findTechnique("direct").params);
    gl::ParamValues reuse = frameValues(true, 0.1), still = frameValues(false);
    reuse.setValue("temporal.direct", 1);
    still.setValue("accumulate", 1);
    gl::Renderer reused(scene, "direct", reuse, direct, kW, kH),
        moving(scene, "direct", frameValues(false), direct, kW, kH),
        accumulated(scene, "direct", still, direct, kW, kH), photon(scene, "photon", reuse, photonValues(), kW, kH);
    for (gl::Renderer* r : {&reused, &moving, &accumulated, &photon}) r->renderFrame(false);
    EXPECT_EQ(texels(reused), 0.0) << "the ratio estimator casts shadow rays";
    EXPECT_GT(texels(moving), 0.0) << "the moving form reads the emitter's cube";
    EXPECT_GT(texels(accumulated), 0.0) << "still frame 0 is a moving frame";
    EXPECT_GT(texels(photon), 0.0) << "photon says nothing: every map is drawn";
    accumulated.renderFrame(false);
    ASSERT_EQ(accumulated.frame().sampler().stillIndex(), 1);
    EXPECT_EQ(texels(accumulated), 0.0) << "still frames cast shadow rays";
}

// The point gathers read no shadow map where shadow rays light their points and hits (pointLightDefines:
// punctual lights, shadow.still=rays), so that their still frames draw none; the emitting triangles' cube,
// which lights the points of cornell-area, and shadow.still=maps keep them. Frame 0 is a moving frame, whose
// direct pass reads the maps. The images are checked elsewhere (ContactShadowTest: the points against the
// closed form with the rays).
TEST_F(TemporalRendererTest, PointGathersDrawNoShadowMapWhereRaysLightThePoints)
{
    const auto texels = [](const gl::Renderer& r) {
        for (const gl::Counter& c : r.frameCounters())
            if (c.name == "shadow.texels") return c.value;
        return -1.0;
    };
    // The shadow texels of still frame 1 of `technique` on `scene`.
    const auto stillTexels = [&](const char* sceneName, const char* technique, const char* still) {
        gl::ParamValues frame = frameValues(false), values(gl::findTechnique(technique).params);
        frame.setValue("accumulate", 1);
        frame.set(gl::frameParams(), "shadow.still", still);
        values.setValue("points", 1024);
        const core::Scene scene = core::makeCornell(sceneName); // the Renderer keeps a reference
        gl::Renderer r(scene, technique, frame, values, kW, kH);
        r.renderFrame(false);
        EXPECT_GT(texels(r), 0.0) << technique << ": frame 0 is a moving frame";
        r.renderFrame(false);
        EXPECT_EQ(r.frame().sampler().stillIndex(), 1);
        return texels(r);
    };
    // Both techniques ask pointLightReadsShadowMaps; its cases on one of them.
    EXPECT_EQ(stillTexels("cornell-spot", "pointproj", "rays"), 0.0) << "rays light the points";
    EXPECT_EQ(stillTexels("cornell-spot", "microrender", "rays"), 0.0) << "rays light the points";
    EXPECT_GT(stillTexels("cornell-spot", "microrender", "maps"), 0.0) << "the maps light them";
    EXPECT_GT(stillTexels("cornell-area", "microrender", "rays"), 0.0) << "the emitter's cube lights them";
}

} // namespace
} // namespace bounce
