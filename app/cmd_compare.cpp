// bounce compare: the error figures of an image against a reference (core/metrics.h), optionally with
// an error heat map and a JSON record.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/options.h"
#include "core/image.h"
#include "core/metrics.h"

namespace bounce::app {

namespace {

const char* kUsage =
    "usage: bounce compare IMAGE REFERENCE [--block N] [--mask-above L] [--heatmap FILE] [--json FILE]\n"
    "\n"
    "Error figures of IMAGE against REFERENCE (.exr or .pfm; IMAGE the same size or an integer multiple of\n"
    "it, then box-filtered down to it first), over the RGB values of every pixel: RMSE, relative RMSE\n"
    "(RMSE / mean of the reference), relative MSE (mean (a-r)^2 / (r^2 + 0.01)), mean absolute error, max\n"
    "error, the means (of all channels, and of R, G and B each) and SSIM of the luminance (11x11 Gaussian\n"
    "window, sigma 1.5, dynamic range = the 99th percentile of the reference's luminance). NaN/Inf values\n"
    "are counted and reported; any of them makes every error figure infinite, SSIM 0, and the exit status 1.\n"
    "\n"
    "  --block    compare the means of NxN-pixel blocks (at the reference's size; N divides it) instead of\n"
    "             pixels: what is left is shading error, not where a sample fell inside a pixel   [1]\n"
    "  --mask-above\n"
    "             leave out the blocks that hold a reference pixel of luminance above L or touch one\n"
    "             (a visible emitter, whose edges alias against any box-filtered reference); the\n"
    "             figures then cover the remaining blocks, both images black in the masked ones\n"
    "  --heatmap  write the per-pixel relative error as a colour ramp (.png, or .exr/.pfm): black <= 0.01%,\n"
    "             blue 0.1%, cyan, green 3%, yellow, red 100%, white >= 1000%; magenta = NaN/Inf\n"
    "  --json     write the figures as JSON\n";

std::string fmt(double v)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// JSON has no infinity: +-inf is written as the string "inf" / "-inf" (Python's float() reads it), NaN as null.
nlohmann::json number(double v)
{
    if (std::isfinite(v)) return v;
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return nullptr;
}

} // namespace

int cmdCompare(const Args& args)
{
    const Options o(args, {{"heatmap"}, {"json"}, {"block"}, {"mask-above"}}, kUsage);
    if (o.helpRequested()) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (o.positional().size() != 2)
        throw UsageError("needs exactly two images, IMAGE and REFERENCE (got " + std::to_string(o.positional().size()) +
                         ")\n\n" + kUsage);
    const std::string pathA = o.positional()[0], pathB = o.positional()[1];
    if (o.has("heatmap")) {
        const std::string ext = std::filesystem::path(o.get("heatmap")).extension().string();
        if (ext != ".png" && ext != ".exr" && ext != ".pfm")
            throw UsageError("--heatmap must end in .png, .exr or .pfm, not '" + o.get("heatmap") + "'");
    }

    core::Image a, b;
    try {
        a = core::readImage(pathA);
        b = core::readImage(pathB);
    } catch (const core::ImageError& e) {
        throw UsageError(e.what());
    }

    if (a.width != b.width || a.height != b.height) {
        if (a.width % b.width != 0 || a.height % b.height != 0 || a.width / b.width != a.height / b.height)
            throw UsageError("the images differ in size: " + pathA + " is " + std::to_string(a.width) + "x" +
                             std::to_string(a.height) + ", " + pathB + " is " + std::to_string(b.width) + "x" +
                             std::to_string(b.height) +
                             "; compare images of the same size or an image an integer multiple of the reference");
        a = core::boxDownsample(a, b.width, b.height);
    }
    const int block = o.getInt("block", 1, 1, std::min(b.width, b.height));
    if (b.width % block != 0 || b.height % block != 0)
        throw UsageError("--block " + std::to_string(block) + " does not divide the reference's size " +
                         std::to_string(b.width) + "x" + std::to_string(b.height));
    std::size_t masked = 0;
    if (o.has("mask-above")) {
        const double limit = o.getDouble("mask-above", 1.0, 0.0, 1e30);
        const std::vector<bool> mask = core::blocksAbove(b, block, float(limit));
        a = core::blanked(core::boxDownsample(a, b.width / block, b.height / block), mask);
        b = core::blanked(core::boxDownsample(b, b.width / block, b.height / block), mask);
        masked = std::size_t(std::count(mask.begin(), mask.end(), true));
    } else if (block > 1) {
        a = core::boxDownsample(a, b.width / block, b.height / block);
        b = core::boxDownsample(b, b.width / block, b.height / block);
    }

    const core::ImageMetrics m = core::compareImages(a, b);
    std::printf("image:          %s\n", pathA.c_str());
    std::printf("reference:      %s\n", pathB.c_str());
    std::printf("compared:       %dx%d %s, %zu masked\n", m.width, m.height, block > 1 ? "block means" : "pixels",
                masked);
    std::printf("RMSE:           %s\n", fmt(m.rmse).c_str());
    std::printf("relative RMSE:  %s\n", fmt(m.relativeRmse).c_str());
    std::printf("relative MSE:   %s\n", fmt(m.relativeMse).c_str());
    std::printf("MAE:            %s\n", fmt(m.mae).c_str());
    std::printf("max error:      %s\n", fmt(m.maxError).c_str());
    std::printf("SSIM:           %s\n", fmt(m.ssim).c_str());
    std::printf("means:          %s (image), %s (reference)\n", fmt(m.meanImage).c_str(), fmt(m.meanReference).c_str());
    std::printf("channel means:  R %s / %s, G %s / %s, B %s / %s (image / reference)\n",
                fmt(m.channelMeanImage[0]).c_str(), fmt(m.channelMeanReference[0]).c_str(),
                fmt(m.channelMeanImage[1]).c_str(), fmt(m.channelMeanReference[1]).c_str(),
                fmt(m.channelMeanImage[2]).c_str(), fmt(m.channelMeanReference[2]).c_str());
    std::printf("non-finite:     %zu values in the image, %zu in the reference\n", m.nonFiniteImage,
                m.nonFiniteReference);

    if (o.has("heatmap")) {
        const std::filesystem::path p = o.get("heatmap");
        if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
        core::writeImage(p.string(), core::errorHeatmap(a, b));
        std::printf("heat map:       %s\n", p.string().c_str());
    }
    if (o.has("json")) {
        nlohmann::json j;
        j["image"] = pathA;
        j["reference"] = pathB;
        j["width"] = m.width;
        j["height"] = m.height;
        j["block"] = block;
        j["maskedBlocks"] = masked;
        j["rmse"] = number(m.rmse);
        j["relativeRmse"] = number(m.relativeRmse);
        j["relativeMse"] = number(m.relativeMse);
        j["relativeMseEpsilon"] = core::kRelativeMseEpsilon;
        j["mae"] = number(m.mae);
        j["maxError"] = number(m.maxError);
        j["ssim"] = number(m.ssim);
        j["meanImage"] = number(m.meanImage);
        j["meanReference"] = number(m.meanReference);
        j["channelMeanImage"] = {number(m.channelMeanImage[0]), number(m.channelMeanImage[1]),
                                 number(m.channelMeanImage[2])};
        j["channelMeanReference"] = {number(m.channelMeanReference[0]), number(m.channelMeanReference[1]),
                                     number(m.channelMeanReference[2])};
        j["nonFiniteImage"] = m.nonFiniteImage;
        j["nonFiniteReference"] = m.nonFiniteReference;
        const std::filesystem::path p = o.get("json");
        if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
        core::writeFileAtomic(p.string(), j.dump(2) + "\n");
        std::printf("json:           %s\n", p.string().c_str());
    }
    if (!m.allFinite()) {
        std::fprintf(stderr,
                     "bounce compare: %zu NaN/Inf values in the image, %zu in the reference: the error is "
                     "infinite\n",
                     m.nonFiniteImage, m.nonFiniteReference);
        return 1;
    }
    return 0;
}

} // namespace bounce::app
