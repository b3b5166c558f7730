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
//     `bounce render` writes it: a tight tolerance, and shadow interiors are in it;
//   - the whole image, GL rendered at kSuper x kSuper samples per pixel and averaged (the path tracer's
//     box filter): edges included, so shadow-map resolution and edge sampling are what remains.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/image.h"
#include "core/metrics.h"
#include "gl/renderer.h"
#include "ref/reference.h"
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
core::Image renderGlDirect(int supersample)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("shadow.size", 2048);
    frameValues.setValue("shadow.pcf", 0); // the path tracer's shadows are hard
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

} // namespace
} // namespace bounce
