// The one image assertion of the test suites: two images, a metric, a tolerance and the reason for that
// tolerance. On failure (or any non-finite value) it writes what is needed to see why, next to the test
// log: both images as EXR (the data) and PNG (to look at) and the error heat map (core::errorHeatmap),
// into $TEST_OUTPUT_DIR/<Suite>.<Test>/ when that variable is set, else into the build's
// Testing/images/<Suite>.<Test>/ (build/Testing/images/...). The files are <name>.got.{exr,png},
// <name>.want.{exr,png} and <name>.error.png.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"

namespace bounce::testing {

struct ImageMetric {
    enum class Kind {
        RelativeRmse,  // sqrt(mean (got - want)^2) / mean(want), core::relativeRmse (over the mask, if any)
        MaxAbs,        // max |got - want|
        MeanRelative,  // |mean(got) - mean(want)| / mean(want): the overall energy
        BlockMeans,    // max over block x block tiles of |tile mean(got) - tile mean(want)| / mean(want)
        ValuesOutside, // how many values have |got - want| > absTol + relTol |want|
    };
    Kind kind = Kind::RelativeRmse;
    int block = 0;
    double absTol = 0.0, relTol = 0.0;

    static ImageMetric relativeRmse() { return {Kind::RelativeRmse}; }
    static ImageMetric maxAbs() { return {Kind::MaxAbs}; }
    static ImageMetric meanRelative() { return {Kind::MeanRelative}; }
    static ImageMetric blockMeans(int block) { return {Kind::BlockMeans, block}; }
    static ImageMetric valuesOutside(double absTol, double relTol) { return {Kind::ValuesOutside, 0, absTol, relTol}; }
    std::string describe() const;
};

// The metric's value. `mask` (width x height, row 0 at the top), when given, limits every metric to the
// pixels it sets. Non-finite values are left out (ImageMetric counts nothing for them); sizes must agree.
double measureImages(const core::Image& got, const core::Image& want, const ImageMetric& metric,
                     const std::vector<bool>* mask = nullptr);

// EXPECTs measure(got, want) <= tolerance, every value of both images finite, and want not all black
// (a comparison against black says nothing, except for ValuesOutside and MaxAbs where it is exact).
// On failure writes the images (see above) and names them in the failure. Returns the measured value.
double expectImagesClose(const std::string& name, const core::Image& got, const core::Image& want,
                         const ImageMetric& metric, double tolerance, const std::string& reason,
                         const std::vector<bool>* mask = nullptr);

// Where the failure images of the running test go (created on demand).
std::filesystem::path testImageDir();
// Writes <name>.got/.want (EXR and PNG) and <name>.error.png there; returns the folder. For tests whose
// check is their own (a per-pixel noise bound) and that only need the images on failure.
std::filesystem::path writeComparisonImages(const std::string& name, const core::Image& got, const core::Image& want);

} // namespace bounce::testing
