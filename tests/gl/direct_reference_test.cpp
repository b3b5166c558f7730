// The OpenGL `direct` frame against the CPU path tracer's `direct` light paths (ref/) on cornell-spot.
// The issue: "`direct` from `bounce render` (OpenGL) matches `bounce reference --paths direct` on
// `cornell-spot` within a stated relative RMSE (shadow-map resolution is the only expected
// difference)". Two independent renderers (a rasteriser with shadow maps; Embree with shadow rays) meet
// on the same scene, camera and pixel grid (row 0 at the top); neither image comes from the other.
//
// One more difference than the issue names: the path tracer box-filters each pixel (ref/README.md), the
// rasteriser shades the pixel centre, so pixels crossed by a silhouette, a shadow edge or the spot's
// hard cone edge differ whatever the shadow map. Hence two figures:
//   - interior pixels (the path tracer's samples inside the pixel agree), GL at pixel centres exactly as
//     `bounce render --set edgeAA=0` writes it: a tight tolerance, and shadow interiors are in it;
//   - the whole image, GL rendered at kSuper x kSuper samples per pixel and averaged (the path tracer's
//     box filter): edges included, so shadow-map resolution and edge sampling are what remains.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/brdf.h"
#include "core/cornell.h"
#include "core/image.h"
#include "core/metrics.h"
#include "gl/renderer.h"
#include "ref/reference.h"
#include "tests/gl/cornell_directional.h"
#include "tests/gl/gl_test_fixture.h"
#include "tests/image_expect.h"

namespace bounce {
namespace {

constexpr int kSize = 64;
constexpr int kSuper = 8; // GL samples per pixel side for the box-filtered image (512^2 on llvmpipe)
// Direct light from a point-like spot has no noise inside a pixel without an edge (next-event
// estimation is exact there), so samples only resolve the edges: 1024 spp is ~1.5 s on two cores.
constexpr int kReferenceSpp = 1024;
// The negative control only has to be clearly off: indirect light is 46% of onebounce here (means
// 0.0236 against direct's 0.0127).
constexpr int kOneBounceSpp = 256;
// A pixel is interior when one path-tracer sample's standard deviation (from the variance of the
// mean x spp, summed over channels) is at most this fraction of the pixel's mean: an edge inside the
// pixel makes samples disagree; a smooth gradient over one pixel stays far below 5%.
constexpr double kInteriorSpread = 0.05;

// Interior pixels, GL at pixel centres. Measured 0.0034 over 3677 of 4096 pixels (the black ones
// included: out of the cone, in the blocks' shadows, outside the box); 0.0026 against 4096 spp, so
// part of it is reference noise, the rest the G-buffer's half floats. The bright floor under the spot
// (~25x the image mean) dominates, so this is tight: the GL image 1% too bright reads 0.031, the camera
// turned by a quarter pixel 0.022 (both measured, then undone).
constexpr double kInteriorRelRmse = 0.01;
// The whole image, GL box-filtered over 8x8 samples, hard shadows (shadow.pcf 0, shadow.linear 0) from
// a 2048^2 map. Measured 0.073 (0.081 with the default 1024^2 map, PCF 1, bilinear; 0.066 with
// 4096^2 and a 4096-spp reference): nearly all of it on edge pixels, where 64 regular samples and 1024 random
// ones still see slightly different coverage and the shadow map moves shadow edges by a texel.
constexpr double kWholeRelRmse = 0.12;

struct Reference {
    ref::RenderResult direct, oneBounce;
};

ref::RenderResult renderReference(const core::Scene& scene, ref::LightPaths paths, int spp)
{
    ref::RenderSettings s;
    s.paths = paths;
    s.width = kSize;
    s.height = kSize;
    s.spp = spp;
    s.seed = 7;
    s.progress = false;
    const auto start = std::chrono::steady_clock::now();
    ref::RenderResult r = ref::render(scene, scene.camera, s);
    std::printf("[ reference] %s, %d spp: %.2f s\n", ref::lightPathsName(paths).c_str(), r.spp,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    EXPECT_EQ(r.nonFiniteSamples, 0u) << ref::lightPathsName(paths);
    return r;
}

// The path tracer's images are CPU data: rendered once for both tests of the suite.
const Reference& reference()
{
    static const Reference r = [] {
        const core::Scene scene = core::makeCornell("cornell-spot");
        return Reference{renderReference(scene, ref::LightPaths::Direct, kReferenceSpp),
                         renderReference(scene, ref::LightPaths::OneBounce, kOneBounceSpp)};
    }();
    return r;
}

// What `bounce render` gives for direct (hard shadows, a 2048^2 map) at `supersample` x the size,
// box-averaged back to kSize.
core::Image renderGlDirect(int supersample, bool edgeAA = false)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("edgeAA", edgeAA ? 1 : 0);
    frameValues.setValue("shadow.size", 2048);
    frameValues.setValue("shadow.footprint", 0); // every view at 2048^2, not sized from a 32x32 image
    frameValues.setValue("shadow.pcf", 0);       // the path tracer's shadows are hard
    frameValues.setValue("shadow.linear", 0);
    gl::Renderer r(scene, "direct", frameValues, gl::ParamValues(), kSize * supersample, kSize * supersample);
    r.renderFrame();
    const core::Image fine = r.image();
    core::Image out(kSize, kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            glm::dvec3 sum(0.0);
            for (int j = 0; j < supersample; ++j)
                for (int i = 0; i < supersample; ++i)
                    sum += glm::dvec3(fine.at(x * supersample + i, y * supersample + j));
            out.set(x, y, glm::vec3(sum / double(supersample * supersample)));
        }
    return out;
}

std::vector<bool> interiorPixels(const ref::RenderResult& r)
{
    std::vector<bool> interior(std::size_t(kSize) * kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec3 var = r.variance.at(x, y), mean = r.image.at(x, y);
            const double spread = std::sqrt(double(var.x + var.y + var.z) * r.spp);
            interior[std::size_t(y) * kSize + x] = spread <= kInteriorSpread * double(mean.x + mean.y + mean.z);
        }
    return interior;
}

class DirectPathTracerTest : public GlTest {};

TEST_F(DirectPathTracerTest, GlDirectMatchesPathTracerDirect)
{
    const ref::RenderResult& want = reference().direct;
    const std::vector<bool> interior = interiorPixels(want);
    const auto interiorCount = std::count(interior.begin(), interior.end(), true);
    // Enough of the image is judged at the tight tolerance: the floor, the walls, the blocks' shadows.
    ASSERT_GT(interiorCount, kSize * kSize * 3 / 4);

    const core::Image centres = renderGlDirect(1);
    const double interiorError = testing::expectImagesClose(
        "interior", centres, want.image, testing::ImageMetric::relativeRmse(), kInteriorRelRmse,
        "interior pixels: reference noise and half-float G-buffer", &interior);
    std::printf("[ measured ] interior relative RMSE %.4g over %lld pixels\n", interiorError, (long long)interiorCount);

    const core::Image boxed = renderGlDirect(kSuper);
    const core::ImageMetrics m = core::compareImages(boxed, want.image);
    std::printf("[ measured ] whole-image relative RMSE %.4g (GL mean %.5g, reference mean %.5g)\n", m.relativeRmse,
                m.meanImage, m.meanReference);
    testing::expectImagesClose("whole", boxed, want.image, testing::ImageMetric::relativeRmse(), kWholeRelRmse,
                               "edge pixels: 64 regular samples against random ones, shadow-map texels");

    // One sample per pixel with the moving frames' edge antialiasing (gl/frame/edge_antialias.h): the
    // silhouettes' and creases' pixels take the areas each side covers, so the whole image comes closer to
    // the path tracer's box-filtered pixels than the pixel centres do (the shadow edges stay as they were).
    const double centresWhole = core::relativeRmse(centres, want.image);
    const double antialiasedWhole = core::relativeRmse(renderGlDirect(1, true), want.image);
    std::printf("[ measured ] whole image, one sample per pixel: centres %.4g, edges antialiased %.4g\n", centresWhole,
                antialiasedWhole);
    EXPECT_LT(antialiasedWhole, 0.8 * centresWhole);
}

// Negative control: the same two comparisons against the path tracer's onebounce (direct plus one
// indirect reflection) must fail by far, or the tolerances above would not tell direct light from
// direct plus indirect. Measured: interior 0.88, whole image 0.76.
TEST_F(DirectPathTracerTest, PathTracerOneBounceIsClearlyFurther)
{
    const Reference& r = reference();
    const std::vector<bool> interior = interiorPixels(r.direct); // onebounce is noisy everywhere
    const double interiorError =
        testing::measureImages(renderGlDirect(1), r.oneBounce.image, testing::ImageMetric::relativeRmse(), &interior);
    const double wholeError = core::relativeRmse(renderGlDirect(kSuper), r.oneBounce.image);
    const core::ImageMetrics means = core::compareImages(r.oneBounce.image, r.direct.image);
    std::printf("[ measured ] against onebounce: interior %.4g, whole image %.4g (onebounce mean %.5g, direct %.5g)\n",
                interiorError, wholeError, means.meanImage, means.meanReference);
    EXPECT_GT(interiorError, 10.0 * kInteriorRelRmse);
    EXPECT_GT(wholeError, 2.0 * kWholeRelRmse);
}

// ---------------------------------------------------------------------------------------------------
// Every light kind and every Cornell variant (issue 17: doubling the area light's form factor changed
// cornell-area's direct image by 56% and no test noticed). Each variant's GL direct light (hard shadows
// from a 2048^2 map) against the path tracer's direct light at kSmall x kSmall, judged where the two
// renderers must agree whatever their sampling:
//   - punctual lights (point, spot, directional): the interior pixels (as above: the path tracer's
//     samples inside the pixel agree, so no edge or shadow boundary crosses it), GL at pixel centres as
//     `bounce render` writes it. Box-filtering GL here would bring in what the interior test keeps out: a
//     texel of light that the shadow map's bias lets under the slats' feet reads 0.06 in pixels where
//     256 random samples found nothing;
//   - area lights: next-event estimation is noisy everywhere, so the whole image, GL box-filtered over
//     kSuper x kSuper samples as the path tracer's pixels are, without the pixels that see the emitter
//     and their neighbours (the emitter's radiance, 17 W/(m^2 sr) against walls below 1, aliases at its
//     edges: bounce bench leaves them out for the same reason). The mask comes from the reference:
//     pixels brighter than any lit wall.
// Tolerances are the measured figures (printed) with a margin; a doubled form factor (relative error 1)
// or a punctual light off by a factor 1.2 (0.2) are far outside them.

constexpr int kSmall = 32;

struct LightCase {
    const char* name;         // a Cornell variant, or "cornell-directional"
    bool area;                // judged on the masked whole image, else on interior pixels
    int spp;                  // the reference's
    double relRmse;           // tolerance
    const char* whyTolerance; // what remains
    double stillRelRmse;      // tolerance of the still frames' test (ConvergedStillFrames...)
};

core::Scene lightCaseScene(const std::string& name)
{
    return name == "cornell-directional" ? test::cornellDirectional() : core::makeCornell(name);
}

ref::RenderResult lightCaseReference(const core::Scene& scene, int spp, double* seconds = nullptr)
{
    ref::RenderSettings s;
    s.paths = ref::LightPaths::Direct;
    s.width = s.height = kSmall;
    s.spp = spp;
    s.seed = 11;
    s.progress = false;
    const auto start = std::chrono::steady_clock::now();
    ref::RenderResult r = ref::render(scene, scene.camera, s);
    if (seconds) *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

core::Image glDirect(const core::Scene& scene, int supersample)
{
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("shadow.size", 2048);
    frameValues.setValue("shadow.footprint", 0); // every view at 2048^2, not sized from a 32x32 image
    frameValues.setValue("shadow.pcf", 0);
    frameValues.setValue("shadow.linear", 0);
    gl::Renderer r(scene, "direct", frameValues, gl::ParamValues(), kSmall * supersample, kSmall * supersample);
    r.renderFrame();
    return core::boxDownsample(r.image(), kSmall, kSmall);
}

// Pixels of the reference whose samples agree (no edge inside), as interiorPixels() at kSmall.
std::vector<bool> agreeingPixels(const ref::RenderResult& r)
{
    std::vector<bool> keep(std::size_t(kSmall) * kSmall);
    for (int y = 0; y < kSmall; ++y)
        for (int x = 0; x < kSmall; ++x) {
            const glm::vec3 var = r.variance.at(x, y), mean = r.image.at(x, y);
            keep[std::size_t(y) * kSmall + x] =
                std::sqrt(double(var.x + var.y + var.z) * r.spp) <= kInteriorSpread * double(mean.x + mean.y + mean.z);
        }
    return keep;
}

// Every pixel but those brighter than 1 W/(m^2 sr) (the emitter: lit walls stay far below) and their
// eight neighbours.
std::vector<bool> withoutEmitters(const core::Image& reference)
{
    std::vector<bool> keep(std::size_t(kSmall) * kSmall, true);
    for (int y = 0; y < kSmall; ++y)
        for (int x = 0; x < kSmall; ++x) {
            if (core::luminance(reference.at(x, y)) <= 1.0f) continue;
            for (int j = std::max(y - 1, 0); j <= std::min(y + 1, kSmall - 1); ++j)
                for (int i = std::max(x - 1, 0); i <= std::min(x + 1, kSmall - 1); ++i)
                    keep[std::size_t(j) * kSmall + i] = false;
        }
    return keep;
}

class EveryLightKindTest : public GlTest, public ::testing::WithParamInterface<LightCase> {};

TEST_P(EveryLightKindTest, GlDirectMatchesPathTracerDirect)
{
    const LightCase& c = GetParam();
    const core::Scene scene = lightCaseScene(c.name);
    double seconds = 0.0;
    const ref::RenderResult want = lightCaseReference(scene, c.spp, &seconds);
    EXPECT_EQ(want.nonFiniteSamples, 0u);
    const std::vector<bool> judged = c.area ? withoutEmitters(want.image) : agreeingPixels(want);
    const auto count = std::count(judged.begin(), judged.end(), true);
    ASSERT_GT(count, kSmall * kSmall / 3) << "a good part of the image is judged";
    const core::Image got = glDirect(scene, c.area ? kSuper : 1);
    const core::ImageMetrics means = core::compareImages(got, want.image);
    const double error =
        testing::expectImagesClose(std::string("direct-") + c.name, got, want.image,
                                   testing::ImageMetric::relativeRmse(), c.relRmse, c.whyTolerance, &judged);
    std::printf("[ measured ] %s: relative RMSE %.4g over %lld of %d pixels (GL mean %.5g, reference mean %.5g, "
                "%d spp in %.2f s)\n",
                c.name, error, (long long)count, kSmall * kSmall, means.meanImage, means.meanReference, want.spp,
                seconds);
}

// Issue 26: the frame's own direct light, as `bounce render --frames N` gives it (default shadow maps, PCF
// and all: still frames switch to jittered single taps), over kStillFrames still frames, against the path
// tracer on the whole image, edges included (only the visible emitter left out): jittered pixel centres
// average to the path tracer's box-filtered pixels, jittered shadow maps to hard shadows, the area
// lights' sample points to soft ones.
constexpr int kStillFrames = 64;

TEST_P(EveryLightKindTest, ConvergedStillFramesMatchPathTracerEdgesIncluded)
{
    const LightCase& c = GetParam();
    const core::Scene scene = lightCaseScene(c.name);
    const ref::RenderResult want = lightCaseReference(scene, c.spp);
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("shadow.size", 512);
    gl::Renderer r(scene, "direct", frameValues, gl::ParamValues(), kSmall, kSmall);
    for (int i = 0; i <= kStillFrames; ++i) r.renderFrame(false);
    ASSERT_EQ(r.stillFrames(), kStillFrames);
    const std::vector<bool> judged = withoutEmitters(want.image);
    const double error = testing::expectImagesClose(std::string("still-") + c.name, r.image(), want.image,
                                                    testing::ImageMetric::relativeRmse(), c.stillRelRmse,
                                                    "reference noise, the still frames' own", &judged);
    gl::Renderer one(scene, "direct", frameValues, gl::ParamValues(), kSmall, kSmall);
    one.renderFrame(false);
    const double single =
        testing::measureImages(one.image(), want.image, testing::ImageMetric::relativeRmse(), &judged);
    std::printf("[ measured ] %s: relative RMSE %.4g after %d still frames, %.4g for one frame\n", c.name, error,
                kStillFrames, single);
    // Tolerances (stillRelRmse): the measured figure with a margin. Spot and slats stay high at 32x32: the
    // coverage of a pixel that a shadow edge under the spot (25x the image mean) crosses is estimated from
    // 64 jittered samples (measured 0.12 and 0.34; 256 frames: spot 0.042). What every case must show
    // whatever the scene: the still frames remove most of one frame's error.
    EXPECT_LT(error, 0.35 * single);
}

INSTANTIATE_TEST_SUITE_P(
    Direct, EveryLightKindTest,
    ::testing::Values(
        LightCase{"cornell-spot", false, 256, 0.03, "reference noise, half-float G-buffer", 0.18},
        LightCase{"cornell-slats", false, 256, 0.03, "reference noise, half-float G-buffer", 0.5},
        LightCase{"cornell-point", false, 256, 0.08,
                  "pixel centre against pixel mean: 1/r^2 on the ceiling just above the light is "
                  "convex, its centres read up to 5% above the means (measured 0.058)",
                  0.05},
        LightCase{"cornell-point-ceiling", false, 256, 0.03, "reference noise, half-float G-buffer", 0.07},
        LightCase{"cornell-directional", false, 256, 0.03, "reference noise, half-float G-buffer", 0.09},
        LightCase{"cornell-area", true, 1024, 0.15, "reference noise, penumbrae, shadow-map texels", 0.08},
        LightCase{"cornell-glossy", true, 1024, 0.15,
                  "as cornell-area, and the metal block's glossy lobe evaluated towards the "
                  "emitter's centroid (lighting.glsl)",
                  0.08}),
    [](const ::testing::TestParamInfo<LightCase>& info) {
        std::string n = info.param.name;
        for (char& ch : n)
            if (ch == '-') ch = '_';
        return n;
    });

} // namespace
} // namespace bounce
