// Convergence and reproducibility of the reference: RMSE against a high-sample render falls as
// 1/sqrt(spp); the same seed gives the same bits whatever the thread count; the noise target stops the
// render where the reported noise says it should, and the reported noise matches the measured error.
#include <cmath>

#include <gtest/gtest.h>

#include "core/metrics.h"
#include "tests/ref/test_scenes.h"

namespace {

using namespace bounce;
using namespace bounce::testing;
using ref::LightPaths;

TEST(Convergence, RmseFallsAsOneOverSqrtSpp)
{
    const core::Scene s = boxRoom(true);
    const int size = 20;
    // The high-sample image uses another seed: the low-sample renders must not share its random streams.
    const ref::RenderResult high = ref::render(s, s.camera, settings(LightPaths::Full, size, 1024, 99));
    double previous = 0.0;
    for (int spp : {4, 16, 64}) {
        // Averaged over 3 seeds to tame the spread of a single RMSE.
        double mse = 0.0;
        for (std::uint64_t seed : {1u, 2u, 3u}) {
            const ref::RenderResult r = ref::render(s, s.camera, settings(LightPaths::Full, size, spp, seed));
            const double e = core::rmse(r.image, high.image);
            mse += e * e / 3.0;
        }
        const double rmse = std::sqrt(mse);
        if (previous > 0.0) {
            // Expected ratio for 4x the samples: sqrt((1/n + 1/1024) / (1/4n + 1/1024)), about 2 (1.98 at n = 4,
            // 1.88 at n = 16: the reference's own noise). Accept 25% either way.
            const double n = spp / 4.0;
            const double expected = std::sqrt((1.0 / n + 1.0 / 1024) / (1.0 / spp + 1.0 / 1024));
            EXPECT_NEAR(previous / rmse, expected, 0.25 * expected) << spp << " spp";
        }
        previous = rmse;
    }
}

TEST(Convergence, SameSeedSameBitsAnyThreadCount)
{
    const core::Scene s = boxRoom(true);
    ref::RenderSettings one = settings(LightPaths::Full, 20, 6, 42);
    one.threads = 1;
    ref::RenderSettings two = one;
    two.threads = 2;
    ref::RenderSettings many = one;
    many.threads = 7; // more threads than cores: a different split of the tiles
    const ref::RenderResult a = ref::render(s, s.camera, one), b = ref::render(s, s.camera, two);
    const ref::RenderResult c = ref::render(s, s.camera, many);
    EXPECT_EQ(a.image.rgb, b.image.rgb);
    EXPECT_EQ(a.image.rgb, c.image.rgb);
    EXPECT_EQ(a.variance.rgb, b.variance.rgb);
    EXPECT_EQ(a.rays, b.rays);
    ref::RenderSettings other = two;
    other.seed = 43;
    EXPECT_NE(ref::render(s, s.camera, other).image.rgb, a.image.rgb);
}

TEST(Convergence, NoiseTargetIsReachedAndHonest)
{
    const core::Scene s = boxRoom(true);
    ref::RenderSettings rs = settings(LightPaths::Direct, 16, 0, 5);
    rs.targetNoise = 0.03;
    const ref::RenderResult r = ref::render(s, s.camera, rs);
    EXPECT_TRUE(r.reachedTarget);
    EXPECT_LE(r.relativeNoise, 0.03);
    EXPECT_GE(r.spp, rs.minSpp);
    // Deterministic: the same settings stop at the same count.
    EXPECT_EQ(ref::render(s, s.camera, rs).spp, r.spp);
    // Honest: the reported noise (mean standard error over mean radiance, luminance) against the
    // measured error of the same estimate versus a much better one: mean |error| over mean radiance is
    // sqrt(2/pi) times the mean standard error for Gaussian errors. Pixels on the edge of the visible
    // emitter have two-valued samples, far from Gaussian at this count, so accept a factor 2 either way:
    // this catches a noise figure that is wrong, not one that is imprecise.
    const ref::RenderResult high = ref::render(s, s.camera, settings(LightPaths::Direct, 16, 2048, 77));
    double absErr = 0.0, mean = 0.0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const auto lum = [](const glm::vec3& v) { return 0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z; };
            absErr += std::abs(lum(r.image.at(x, y)) - lum(high.image.at(x, y)));
            mean += lum(high.image.at(x, y));
        }
    const double measured = absErr / mean / std::sqrt(2.0 / 3.14159265358979323846);
    EXPECT_GT(measured, r.relativeNoise / 2.0);
    EXPECT_LT(measured, r.relativeNoise * 2.0);
}

TEST(Convergence, SampleCapWinsOverNoiseTarget)
{
    const core::Scene s = boxRoom(true);
    ref::RenderSettings rs = settings(LightPaths::Full, 8, 20, 5);
    rs.targetNoise = 1e-6; // unreachable
    const ref::RenderResult r = ref::render(s, s.camera, rs);
    EXPECT_EQ(r.spp, 20);
    EXPECT_FALSE(r.reachedTarget);
    EXPECT_GT(r.rays, std::uint64_t(8 * 8 * 20));
    EXPECT_GT(r.raysPerSecond(), 0.0);
}

TEST(Convergence, VarianceImageMatchesSpread)
{
    // The variance of the pixel mean, summed over pixels, against the spread of pixel means over two
    // independent renders (seeds): E[(m1 - m2)^2] = var1 + var2. Indirect light only, so that no
    // handful of pixels on the edge of the visible emitter dominates the sums.
    const core::Scene s = boxRoom(true);
    const int size = 16, spp = 16;
    const ref::RenderResult a = ref::render(s, s.camera, settings(LightPaths::OneBounceIndirect, size, spp, 11));
    const ref::RenderResult b = ref::render(s, s.camera, settings(LightPaths::OneBounceIndirect, size, spp, 12));
    double diff2 = 0.0, var = 0.0;
    for (std::size_t i = 0; i < a.image.rgb.size(); ++i) {
        const double d = double(a.image.rgb[i]) - double(b.image.rgb[i]);
        diff2 += d * d;
        var += double(a.variance.rgb[i]) + double(b.variance.rgb[i]);
    }
    EXPECT_NEAR(diff2 / var, 1.0, 0.3);
}

} // namespace
