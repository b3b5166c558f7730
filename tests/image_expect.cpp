#include "tests/image_expect.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include <gtest/gtest.h>

#include "core/metrics.h"

namespace bounce::testing {

std::string ImageMetric::describe() const
{
    std::ostringstream s;
    switch (kind) {
    case Kind::RelativeRmse: s << "relative RMSE"; break;
    case Kind::MaxAbs: s << "max |got - want|"; break;
    case Kind::MeanRelative: s << "relative difference of the means"; break;
    case Kind::BlockMeans: s << "largest relative difference of " << block << "x" << block << " block means"; break;
    case Kind::ValuesOutside: s << "values outside " << absTol << " + " << relTol << " x |want|"; break;
    }
    return s.str();
}

double measureImages(const core::Image& got, const core::Image& want, const ImageMetric& metric,
                     const std::vector<bool>* mask)
{
    if (got.width != want.width || got.height != want.height || got.rgb.size() != want.rgb.size())
        throw core::MetricsError("images of different sizes");
    if (mask && mask->size() != std::size_t(want.width) * std::size_t(want.height))
        throw core::MetricsError("mask of another size than the images");
    const auto counted = [&](std::size_t pixel) { return !mask || (*mask)[pixel]; };
    const std::size_t pixels = std::size_t(want.width) * std::size_t(want.height);
    double squared = 0.0, sumGot = 0.0, sumWant = 0.0, largest = 0.0, outside = 0.0;
    std::size_t values = 0;
    for (std::size_t p = 0; p < pixels; ++p) {
        if (!counted(p)) continue;
        for (std::size_t c = 0; c < 3; ++c) {
            const double a = got.rgb[p * 3 + c], b = want.rgb[p * 3 + c];
            if (!std::isfinite(a) || !std::isfinite(b)) continue;
            const double d = std::abs(a - b);
            squared += d * d;
            sumGot += a;
            sumWant += b;
            largest = std::max(largest, d);
            outside += d > metric.absTol + metric.relTol * std::abs(b);
            ++values;
        }
    }
    const double meanWant = values ? sumWant / double(values) : 0.0;
    // As core::relativeRmse: 0 when both are 0, +inf when only the reference's mean is.
    const auto relative = [&](double x) { return x == 0.0 ? 0.0 : meanWant > 0.0 ? x / meanWant : INFINITY; };
    switch (metric.kind) {
    case ImageMetric::Kind::RelativeRmse: return relative(values ? std::sqrt(squared / double(values)) : 0.0);
    case ImageMetric::Kind::MaxAbs: return largest;
    case ImageMetric::Kind::MeanRelative: return relative(values ? std::abs(sumGot - sumWant) / double(values) : 0.0);
    case ImageMetric::Kind::ValuesOutside: return outside;
    case ImageMetric::Kind::BlockMeans: break;
    }
    if (metric.block <= 0) throw core::MetricsError("block means need a block size of at least 1");
    double worst = 0.0;
    for (int by = 0; by < want.height; by += metric.block)
        for (int bx = 0; bx < want.width; bx += metric.block) {
            double a = 0.0, b = 0.0;
            std::size_t n = 0;
            for (int y = by; y < std::min(by + metric.block, want.height); ++y)
                for (int x = bx; x < std::min(bx + metric.block, want.width); ++x) {
                    const std::size_t p = std::size_t(y) * std::size_t(want.width) + std::size_t(x);
                    if (!counted(p)) continue;
                    for (std::size_t c = 0; c < 3; ++c) {
                        const double ga = got.rgb[p * 3 + c], wb = want.rgb[p * 3 + c];
                        if (!std::isfinite(ga) || !std::isfinite(wb)) continue;
                        a += ga, b += wb, ++n;
                    }
                }
            if (n) worst = std::max(worst, std::abs(a - b) / double(n));
        }
    return relative(worst);
}

std::filesystem::path testImageDir()
{
    const char* env = std::getenv("TEST_OUTPUT_DIR");
    const std::filesystem::path root =
        env && *env ? std::filesystem::path(env) : std::filesystem::path(BOUNCE_TEST_IMAGE_DIR);
    const ::testing::TestInfo* t = ::testing::UnitTest::GetInstance()->current_test_info();
    if (!t) return root;
    // Parameterised suites and tests have '/' in their names: one folder per test all the same.
    std::string leaf = std::string(t->test_suite_name()) + "." + t->name();
    std::replace(leaf.begin(), leaf.end(), '/', '_');
    return root / leaf;
}

std::filesystem::path writeComparisonImages(const std::string& name, const core::Image& got, const core::Image& want)
{
    const std::filesystem::path dir = testImageDir();
    std::filesystem::create_directories(dir);
    const auto path = [&](const char* suffix) { return (dir / (name + suffix)).string(); };
    core::writeExr(path(".got.exr"), got);
    core::writeExr(path(".want.exr"), want);
    core::writePng(path(".got.png"), got);
    core::writePng(path(".want.png"), want);
    core::writePng(path(".error.png"), core::errorHeatmap(got, want));
    return dir;
}

double expectImagesClose(const std::string& name, const core::Image& got, const core::Image& want,
                         const ImageMetric& metric, double tolerance, const std::string& reason,
                         const std::vector<bool>* mask)
{
    if (got.width != want.width || got.height != want.height || got.rgb.size() != want.rgb.size()) {
        ADD_FAILURE() << name << ": got " << got.width << "x" << got.height << ", want " << want.width << "x"
                      << want.height;
        return INFINITY;
    }
    const core::ImageMetrics all = core::compareImages(got, want);
    const double measured = measureImages(got, want, metric, mask);
    const bool blackMatters =
        metric.kind != ImageMetric::Kind::ValuesOutside && metric.kind != ImageMetric::Kind::MaxAbs;
    // One failure per comparison, with every reason in it and where the images went.
    std::ostringstream problems;
    if (!all.allFinite())
        problems << "\n  non-finite values (" << all.nonFiniteImage << " in got, " << all.nonFiniteReference
                 << " in want)";
    if (blackMatters && !(all.meanReference > 0.0))
        problems << "\n  the reference is black, the comparison says nothing";
    if (!(measured <= tolerance))
        problems << "\n  " << metric.describe() << " " << measured << " > " << tolerance << " (" << reason
                 << "); relative RMSE " << all.relativeRmse << ", max |diff| " << all.maxError << ", means "
                 << all.meanImage << " vs " << all.meanReference;
    if (!problems.str().empty())
        ADD_FAILURE() << name << ":" << problems.str() << "\n  images written to "
                      << writeComparisonImages(name, got, want).string() << "/" << name << ".{got,want}.{exr,png}, "
                      << name << ".error.png";
    return measured;
}

} // namespace bounce::testing
