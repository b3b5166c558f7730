// core/metrics.h against values worked out by hand: constant images (where SSIM has a closed form),
// a single differing value, non-finite values, size mismatches and the heat map's colours.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/metrics.h"

namespace {

using namespace bounce::core;

Image constant(int w, int h, float v)
{
    Image im(w, h);
    for (float& c : im.rgb) c = v;
    return im;
}

// A smooth, non-constant test image.
Image pattern(int w, int h)
{
    Image im(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            im.set(x, y,
                   {0.5f + 0.4f * std::sin(0.3f * float(x)), 0.5f + 0.4f * std::cos(0.2f * float(y)),
                    0.1f * float(x + y) / float(w + h)});
    return im;
}

TEST(Metrics, IdenticalImagesHaveNoError)
{
    const Image a = pattern(40, 30);
    const ImageMetrics m = compareImages(a, a);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.relativeRmse, 0.0);
    EXPECT_EQ(m.relativeMse, 0.0);
    EXPECT_EQ(m.mae, 0.0);
    EXPECT_EQ(m.maxError, 0.0);
    EXPECT_NEAR(m.ssim, 1.0, 1e-12);
    EXPECT_TRUE(m.allFinite());
    EXPECT_EQ(m.valuesCompared, 40u * 30u * 3u);
}

TEST(Metrics, ConstantOffsetClosedForm)
{
    // a = 3, r = 2 everywhere: every difference is 1.
    const Image a = constant(16, 12, 3.0f), r = constant(16, 12, 2.0f);
    const ImageMetrics m = compareImages(a, r);
    EXPECT_DOUBLE_EQ(m.rmse, 1.0);
    EXPECT_DOUBLE_EQ(m.relativeRmse, 0.5);
    EXPECT_NEAR(m.relativeMse, 1.0 / (4.0 + kRelativeMseEpsilon), 1e-12);
    EXPECT_NEAR(relativeMse(a, r, 0.0), 0.25, 1e-12);
    EXPECT_DOUBLE_EQ(m.mae, 1.0);
    EXPECT_DOUBLE_EQ(m.maxError, 1.0);
    EXPECT_DOUBLE_EQ(m.meanReference, 2.0);
    // Constant windows have no variance, so SSIM is its luminance term (Wang et al. 2004, Eq. 13):
    // (2 mu_a mu_r + C1) / (mu_a^2 + mu_r^2 + C1) with L = the 99th percentile of r's luminance = 2,
    // C1 = (0.01 L)^2.
    const double c1 = 0.02 * 0.02;
    EXPECT_NEAR(m.ssim, (12.0 + c1) / (13.0 + c1), 1e-9);
}

// The flicker of a camera-path run's pair of frames (bench "path"): a bias that stays from one frame to the
// next is not flicker, a change of the error is, in closed form; a NaN reads as infinite.
TEST(Metrics, ErrorFlickerIgnoresAStableBiasAndMeasuresAChangingOne)
{
    const Image ra = pattern(20, 10);
    Image rb = ra, a = ra, b = ra;
    for (std::size_t i = 0; i < ra.rgb.size(); ++i) {
        rb.rgb[i] = ra.rgb[i] * 0.5f; // the next frame sees something else
        a.rgb[i] = ra.rgb[i] + 0.25f; // the same bias of +0.25 in both frames
        b.rgb[i] = rb.rgb[i] + 0.25f;
    }
    EXPECT_GT(relativeRmse(a, ra), 0.2);
    EXPECT_NEAR(errorFlicker(a, ra, b, rb), 0.0, 1e-7);
    // Errors of +0.25 then -0.25: a change of 0.5 everywhere over the references' mean.
    for (std::size_t i = 0; i < rb.rgb.size(); ++i) b.rgb[i] = rb.rgb[i] - 0.25f;
    double mean = 0.0;
    for (std::size_t i = 0; i < ra.rgb.size(); ++i) mean += 0.5 * (double(ra.rgb[i]) + rb.rgb[i]);
    mean /= double(ra.rgb.size());
    EXPECT_NEAR(errorFlicker(a, ra, b, rb), 0.5 / mean, 1e-6);
    EXPECT_EQ(errorFlicker(ra, ra, rb, rb), 0.0);
    b.rgb[7] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(errorFlicker(a, ra, b, rb), std::numeric_limits<double>::infinity());
    EXPECT_THROW(errorFlicker(a, ra, pattern(10, 10), rb), MetricsError);
}

TEST(Metrics, OneDifferingValue)
{
    const int w = 40, h = 40;
    Image r = constant(w, h, 1.0f), a = r;
    a.rgb[3 * 437 + 1] = 4.0f; // pixel (17, 10), green: difference 3
    const double n = 3.0 * w * h;
    EXPECT_NEAR(rmse(a, r), std::sqrt(9.0 / n), 1e-12);
    EXPECT_NEAR(relativeRmse(a, r), std::sqrt(9.0 / n), 1e-12);
    EXPECT_NEAR(meanAbsoluteError(a, r), 3.0 / n, 1e-12);
    EXPECT_DOUBLE_EQ(maxError(a, r), 3.0);
    EXPECT_NEAR(relativeMse(a, r, 1.0), 9.0 / 2.0 / n, 1e-12);
    // Only the windows that see the pixel (11 x 11 of 40 x 40) lose similarity.
    EXPECT_LT(ssim(a, r), 1.0);
    EXPECT_GT(ssim(a, r), 1.0 - 121.0 / 1600.0);
}

// The per-channel means: a tint the overall mean hides (R +50%, B -50%, G exact: the overall means
// agree), and a NaN in one channel leaves that channel's mean over its finite values only.
TEST(Metrics, ChannelMeansShowATintTheOverallMeanHides)
{
    Image a(4, 4), r(4, 4);
    for (int i = 0; i < 16; ++i) {
        a.rgb[3 * i + 0] = 3.0f;
        a.rgb[3 * i + 1] = 2.0f;
        a.rgb[3 * i + 2] = 1.0f;
        r.rgb[3 * i + 0] = 2.0f;
        r.rgb[3 * i + 1] = 2.0f;
        r.rgb[3 * i + 2] = 2.0f;
    }
    a.rgb[3 * 5 + 0] = std::numeric_limits<float>::quiet_NaN();
    const ImageMetrics m = compareImages(a, r);
    EXPECT_DOUBLE_EQ(m.channelMeanImage[0], 3.0);
    EXPECT_DOUBLE_EQ(m.channelMeanImage[1], 2.0);
    EXPECT_DOUBLE_EQ(m.channelMeanImage[2], 1.0);
    for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(m.channelMeanReference[c], 2.0) << "channel " << c;
    const ImageMetrics clean = compareImages(Image(a.width, a.height), Image(a.width, a.height));
    EXPECT_DOUBLE_EQ(clean.channelMeanImage[0], 0.0);
    // Without the NaN the overall means agree while R and B are 50% off.
    a.rgb[3 * 5 + 0] = 3.0f;
    const ImageMetrics tinted = compareImages(a, r);
    EXPECT_DOUBLE_EQ(tinted.meanImage, tinted.meanReference);
    EXPECT_DOUBLE_EQ(tinted.channelMeanImage[0] / tinted.channelMeanReference[0], 1.5);
    EXPECT_DOUBLE_EQ(tinted.channelMeanImage[2] / tinted.channelMeanReference[2], 0.5);
}

TEST(Metrics, SsimFallsWithNoiseAndIsSymmetricInStructure)
{
    const Image r = pattern(48, 48);
    Image small = r, large = r;
    for (std::size_t i = 0; i < r.rgb.size(); ++i) {
        const float noise = ((i * 2654435761u) % 1000u) / 1000.0f - 0.5f;
        small.rgb[i] += 0.02f * noise;
        large.rgb[i] += 0.2f * noise;
    }
    const double s1 = ssim(small, r), s2 = ssim(large, r);
    EXPECT_LT(s1, 1.0);
    EXPECT_LT(s2, s1);
    EXPECT_GT(s1, 0.9);
}

TEST(Metrics, SsimRangeIgnoresAFewVeryBrightPixels)
{
    // A visible emitter 1000x brighter than the rest must not make SSIM blind to noise elsewhere: the
    // same noise costs the same similarity with or without three such pixels (far from them).
    Image r = pattern(64, 64);
    Image a = r;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) a.rgb[i] += 0.1f * (((i * 2654435761u) % 1000u) / 1000.0f - 0.5f);
    const double plain = ssim(a, r);
    Image rBright = r, aBright = a;
    for (int x = 0; x < 3; ++x) {
        rBright.set(x, 0, glm::vec3(1000.0f));
        aBright.set(x, 0, glm::vec3(1000.0f));
    }
    EXPECT_LT(plain, 0.99);
    EXPECT_NEAR(ssim(aBright, rBright), plain, 0.02);
}

TEST(Metrics, SsimOfTinyImagesUsesClippedWindows)
{
    // Smaller than the 11x11 window: still a value, and 1 for identical images.
    const Image a = pattern(3, 2);
    EXPECT_NEAR(ssim(a, a), 1.0, 1e-12);
    EXPECT_NEAR(ssim(constant(3, 2, 3.0f), constant(3, 2, 2.0f)), (12.0 + 4e-4) / (13.0 + 4e-4), 1e-9);
}

TEST(Metrics, RelativeRmseOfBlackReference)
{
    const Image black = constant(4, 4, 0.0f);
    EXPECT_EQ(relativeRmse(black, black), 0.0);
    EXPECT_TRUE(std::isinf(relativeRmse(constant(4, 4, 1.0f), black)));
}

TEST(Metrics, DifferentSizesThrow)
{
    EXPECT_THROW(compareImages(Image(4, 4), Image(4, 5)), MetricsError);
    EXPECT_THROW(rmse(Image(4, 4), Image(5, 4)), MetricsError);
    EXPECT_THROW(errorHeatmap(Image(4, 4), Image(5, 4)), MetricsError);
    EXPECT_THROW(compareImages(Image(), Image()), MetricsError);
    try {
        ssim(Image(4, 4), Image(8, 2));
        FAIL();
    } catch (const MetricsError& e) {
        EXPECT_NE(std::string(e.what()).find("4x4"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("8x2"), std::string::npos);
    }
}

TEST(Metrics, NonFiniteValuesAreCountedAndMakeEveryErrorInfinite)
{
    const Image r = pattern(8, 8);
    Image a = r;
    a.rgb[5] = std::numeric_limits<float>::quiet_NaN();
    a.rgb[17] = std::numeric_limits<float>::infinity();
    Image r2 = r;
    r2.rgb[40] = -std::numeric_limits<float>::infinity();
    const ImageMetrics m = compareImages(a, r2);
    EXPECT_EQ(m.nonFiniteImage, 2u);
    EXPECT_EQ(m.nonFiniteReference, 1u);
    EXPECT_FALSE(m.allFinite());
    EXPECT_EQ(m.valuesCompared, 8u * 8u * 3u - 3u);
    // Every other value is identical, yet no figure may call the image perfect.
    for (double e : {m.rmse, m.relativeRmse, m.relativeMse, m.mae, m.maxError})
        EXPECT_EQ(e, std::numeric_limits<double>::infinity());
    EXPECT_EQ(m.ssim, 0.0);
    EXPECT_EQ(rmse(a, r2), std::numeric_limits<double>::infinity());
    EXPECT_EQ(relativeRmse(a, r), std::numeric_limits<double>::infinity()) << "a NaN in the image alone";
}

// The finding that this guards: an all-NaN image against a valid reference read as RMSE 0, SSIM 1 and a
// reference mean of 0.
TEST(Metrics, AllNanImageIsNeverPerfect)
{
    const Image r = pattern(8, 8);
    Image a = r;
    for (float& v : a.rgb) v = std::numeric_limits<float>::quiet_NaN();
    const ImageMetrics m = compareImages(a, r);
    EXPECT_EQ(m.nonFiniteImage, a.rgb.size());
    EXPECT_EQ(m.rmse, std::numeric_limits<double>::infinity());
    EXPECT_EQ(m.relativeRmse, std::numeric_limits<double>::infinity());
    EXPECT_EQ(m.ssim, 0.0);
    EXPECT_TRUE(std::isnan(m.meanReference)) << "no finite pair: no mean to report";
}

TEST(Metrics, HeatmapColours)
{
    const Image r = constant(4, 1, 1.0f);
    Image a = r;
    // Pixel 0: identical (black). Pixel 1: relative error 1 -> red. Pixel 2: NaN -> magenta.
    // Pixel 3: e = 0.0101 * 3 / (3 + 0.03) = 0.01 -> log10 = -2, a third of the way from cyan to green.
    a.set(1, 0, {2.0f, 2.0f, 2.0f});
    a.set(2, 0, {std::nanf(""), 1.0f, 1.0f});
    a.set(3, 0, glm::vec3(1.0101f));
    // eps is 1% of the reference's mean per-pixel sum (3), so pixel 1's e = 3 / 3.03: just under red.
    const Image hm = errorHeatmap(a, r);
    EXPECT_EQ(hm.at(0, 0), glm::vec3(0.0f));
    EXPECT_NEAR(hm.at(1, 0).x, 1.0f, 1e-6f);
    EXPECT_NEAR(hm.at(1, 0).y, 0.0f, 0.02f);
    EXPECT_NEAR(hm.at(1, 0).z, 0.0f, 1e-6f);
    EXPECT_EQ(hm.at(2, 0), glm::vec3(1.0f, 0.0f, 1.0f));
    EXPECT_NEAR(hm.at(3, 0).x, 0.0f, 1e-3f);
    EXPECT_NEAR(hm.at(3, 0).y, 1.0f, 1e-3f);
    EXPECT_NEAR(hm.at(3, 0).z, 2.0f / 3.0f, 1e-3f);
    // Far beyond 100%: white.
    a.set(0, 0, glm::vec3(100.0f));
    EXPECT_EQ(errorHeatmap(a, r).at(0, 0), glm::vec3(1.0f));
}

// Box downsampling averages whole blocks (a 4x2 image to 2x1: two 2x2 blocks) and refuses sizes that
// do not divide the image.
TEST(Metrics, BoxDownsampleAveragesBlocks)
{
    Image a(4, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) a.set(x, y, glm::vec3(float(x + 4 * y), 1.0f, x < 2 ? 0.0f : 8.0f));
    const Image d = boxDownsample(a, 2, 1);
    ASSERT_EQ(d.width, 2);
    ASSERT_EQ(d.height, 1);
    EXPECT_FLOAT_EQ(d.at(0, 0).x, (0 + 1 + 4 + 5) / 4.0f);
    EXPECT_FLOAT_EQ(d.at(1, 0).x, (2 + 3 + 6 + 7) / 4.0f);
    EXPECT_FLOAT_EQ(d.at(1, 0).y, 1.0f);
    EXPECT_FLOAT_EQ(d.at(1, 0).z, 8.0f);
    EXPECT_EQ(boxDownsample(a, 4, 2).rgb, a.rgb);
    EXPECT_THROW(boxDownsample(a, 3, 1), std::invalid_argument);
    EXPECT_THROW(boxDownsample(a, 0, 1), std::invalid_argument);
}

} // namespace
