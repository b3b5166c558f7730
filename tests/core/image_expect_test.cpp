// The suites' one image assertion (tests/image_expect.h): each metric against a closed form, and a
// failing comparison writes both images (EXR and PNG) and the heat map where it says.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include "tests/image_expect.h"

namespace bounce {
namespace {

using testing::ImageMetric;

core::Image constant(int w, int h, float v)
{
    core::Image img(w, h);
    for (float& x : img.rgb) x = v;
    return img;
}

// want = 2 everywhere; got = 2 except one pixel of 4x4 at 6 (all channels): 16 pixels, 48 values.
TEST(ImageExpect, MetricsMatchClosedForms)
{
    const core::Image want = constant(4, 4, 2.0f);
    core::Image got = want;
    got.set(1, 2, glm::vec3(6.0f));
    // RMSE = sqrt(3 * 16 / 48) = 1, over the mean 2.
    EXPECT_NEAR(testing::measureImages(got, want, ImageMetric::relativeRmse()), 0.5, 1e-12);
    EXPECT_NEAR(testing::measureImages(got, want, ImageMetric::maxAbs()), 4.0, 1e-12);
    // Means 2 + 12/48 = 2.25 against 2.
    EXPECT_NEAR(testing::measureImages(got, want, ImageMetric::meanRelative()), 0.125, 1e-12);
    // 2x2 blocks: the block holding the pixel is off by 4/4 = 1, over the mean 2.
    EXPECT_NEAR(testing::measureImages(got, want, ImageMetric::blockMeans(2)), 0.5, 1e-12);
    EXPECT_NEAR(testing::measureImages(got, want, ImageMetric::blockMeans(4)), 0.125, 1e-12);
    EXPECT_EQ(testing::measureImages(got, want, ImageMetric::valuesOutside(1.0, 1.0)), 3.0); // 4 > 1 + 2
    EXPECT_EQ(testing::measureImages(got, want, ImageMetric::valuesOutside(1.0, 2.0)), 0.0); // 4 <= 1 + 4
    // A mask without that pixel: identical images.
    std::vector<bool> mask(16, true);
    mask[2 * 4 + 1] = false;
    EXPECT_EQ(testing::measureImages(got, want, ImageMetric::relativeRmse(), &mask), 0.0);
    EXPECT_EQ(testing::measureImages(got, want, ImageMetric::maxAbs(), &mask), 0.0);
    // 1x1 and 3x5 images.
    EXPECT_NEAR(testing::measureImages(constant(1, 1, 3.0f), constant(1, 1, 2.0f), ImageMetric::relativeRmse()), 0.5,
                1e-12);
    EXPECT_NEAR(testing::measureImages(constant(3, 5, 1.0f), constant(3, 5, 2.0f), ImageMetric::blockMeans(2)), 0.5,
                1e-12);
    EXPECT_THROW(testing::measureImages(constant(3, 5, 1.0f), constant(5, 3, 1.0f), ImageMetric::maxAbs()),
                 std::runtime_error);
}

TEST(ImageExpect, PassesWithinTolerance)
{
    const core::Image want = constant(8, 8, 1.0f);
    const core::Image got = constant(8, 8, 1.001f);
    EXPECT_NEAR(testing::expectImagesClose("close", got, want, ImageMetric::relativeRmse(), 2e-3, "test"), 1e-3, 1e-6);
}

// A failure writes <name>.got/.want.{exr,png} and <name>.error.png under $TEST_OUTPUT_DIR/<Suite>.<Test>;
// NaN fails whatever the metric says; a black reference fails a relative metric.
TEST(ImageExpect, FailureWritesTheImagesAndTheHeatMap)
{
    const std::filesystem::path root = std::filesystem::path(BOUNCE_TEST_OUT) / "image_expect";
    std::filesystem::remove_all(root);
    ::setenv("TEST_OUTPUT_DIR", root.c_str(), 1);
    const core::Image want = constant(8, 8, 1.0f);
    const core::Image got = constant(8, 8, 1.5f);
    EXPECT_NONFATAL_FAILURE(testing::expectImagesClose("far", got, want, ImageMetric::relativeRmse(), 0.1, "why"),
                            "relative RMSE 0.5 > 0.1 (why)");
    const std::filesystem::path dir = root / "ImageExpect.FailureWritesTheImagesAndTheHeatMap";
    for (const char* f : {"far.got.exr", "far.want.exr", "far.got.png", "far.want.png", "far.error.png"})
        EXPECT_TRUE(std::filesystem::is_regular_file(dir / f)) << (dir / f);

    core::Image nan = want;
    nan.rgb[5] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NONFATAL_FAILURE(testing::expectImagesClose("nan", nan, want, ImageMetric::maxAbs(), 1e9, "any"),
                            "non-finite values");
    EXPECT_NONFATAL_FAILURE(
        testing::expectImagesClose("black", want, constant(8, 8, 0.0f), ImageMetric::relativeRmse(), 1e9, "any"),
        "the reference is black");
    ::unsetenv("TEST_OUTPUT_DIR");
}

} // namespace
} // namespace bounce
