// Error metrics between an image and its reference (the ground truth of ref/), the figures of every
// speed/error record of the project. All of them run over the three RGB channels of every pixel (no
// crop, no mask); "mean" is the mean over width x height x 3 values.
//
//   rmse          sqrt(mean (a - r)^2)
//   relativeRmse  rmse / mean(r)                       (0 when both are 0, +inf when only mean(r) is 0)
//   relativeMse   mean (a - r)^2 / (r^2 + eps)         eps = 0.01 by default (Rousselle et al. 2011)
//   mae           mean |a - r|
//   maxError      max |a - r|
//   ssim          mean SSIM of the luminance (Wang et al. 2004, Eq. 13) with an 11x11 Gaussian window of
//                 sigma 1.5, K1 = 0.01, K2 = 0.03, C1 = (K1 L)^2, C2 = (K2 L)^2. Radiance has no fixed
//                 white, so the dynamic range L comes from the reference: the 99th percentile of its
//                 luminance (its maximum if that is 0, 1 if it is all black). Not the maximum: a visible
//                 emitter (the Cornell light is ~25x brighter than the walls) would make C1 and C2 so large
//                 that SSIM reads ~1 whatever the noise elsewhere. Windows are clipped at the
//                 image border and their weights renormalised, so every pixel has a value and images
//                 smaller than the window are still measured.
//
// Different sizes throw MetricsError. Non-finite values (NaN, +-Inf) in either image make every error
// figure +inf and SSIM 0: a technique that writes NaN must never look perfect. They are counted
// (ImageMetrics::nonFiniteImage/Reference), and the means are taken over the finite value pairs (NaN when
// there are none). The single-figure functions apply the same rule; use compareImages to see counts.
#pragma once

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "core/image.h"

namespace bounce::core {

struct MetricsError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

inline constexpr double kRelativeMseEpsilon = 1e-2;

struct ImageMetrics {
    int width = 0, height = 0;
    double rmse = 0.0;
    double relativeRmse = 0.0;
    double relativeMse = 0.0;
    double mae = 0.0;
    double maxError = 0.0;
    double ssim = 1.0;
    double meanImage = 0.0;     // mean of a over the finite values
    double meanReference = 0.0; // mean of the reference over the finite values
    // The same means per channel (R, G, B), each over that channel's finite pairs: a tint or a colour
    // bleeding too strongly shows here while the three together balance out.
    std::array<double, 3> channelMeanImage{};
    std::array<double, 3> channelMeanReference{};
    std::size_t nonFiniteImage = 0; // NaN/Inf values (channels) in a
    std::size_t nonFiniteReference = 0;
    std::size_t valuesCompared = 0; // channel pairs where both are finite

    bool allFinite() const { return nonFiniteImage == 0 && nonFiniteReference == 0; }
};

// Every figure at once. Throws MetricsError when the sizes differ or either image is empty.
ImageMetrics compareImages(const Image& a, const Image& reference, double relativeMseEpsilon = kRelativeMseEpsilon);

double rmse(const Image& a, const Image& reference);
double relativeRmse(const Image& a, const Image& reference);
double relativeMse(const Image& a, const Image& reference, double epsilon = kRelativeMseEpsilon);
double meanAbsoluteError(const Image& a, const Image& reference);
double maxError(const Image& a, const Image& reference);
double ssim(const Image& a, const Image& reference);

// The flicker between two frames of a sequence, each with its own reference (bench camera-path runs):
// the RMS of the change of the error image, (a - refA) - (b - refB), over the mean of both references.
// A bias that stays from one frame to the next cancels; noise and error that change do not. 0 when
// everything is 0, +inf for a non-finite value or for black references under a non-zero change.
double errorFlicker(const Image& a, const Image& refA, const Image& b, const Image& refB);

// The box-filtered average of `image` over blocks of (image.width / width) x (image.height / height)
// pixels: what a renderer with width x height box-filtered pixels sees. Throws std::invalid_argument
// unless width and height divide the image's size. Comparing at a coarser size lets a reference of the
// same cost carry less noise per pixel (bounce bench's "reference": {"size": ...}).
Image boxDownsample(const Image& image, int width, int height);

// Which blocks of block x block pixels of `image` (row-major over the (width / block) x (height / block)
// blocks) hold a pixel of luminance above `limit`, or touch such a block: a visible emitter, left out of
// the error figures because its edges alias against any box-filtered reference.
std::vector<bool> blocksAbove(const Image& image, int block, float limit);
// The image with the pixels where mask is true set to black (no error there, no weight in the mean).
Image blanked(Image image, const std::vector<bool>& mask);

// Per-pixel relative error e = sum_c |a_c - r_c| / (sum_c r_c + eps), eps = 1% of the reference's mean
// of sum_c r_c (1e-6 if that is 0, so black regions only light up where a is not black), on a colour
// ramp linear in log10(e): black at or below 1e-4, blue at 1e-3 (0.1%), cyan at 10^-2.25, green at
// 10^-1.5 (3%), yellow at 10^-0.75, red at 1 (100%), white at or above 10. Non-finite pixels (in either
// image) are magenta. Values are linear RGB in [0, 1], ready for writePng with exposure 0.
Image errorHeatmap(const Image& a, const Image& reference);

} // namespace bounce::core
