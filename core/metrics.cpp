#include "core/metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/brdf.h"

namespace bounce::core {

namespace {

void checkSizes(const Image& a, const Image& r)
{
    if (a.width != r.width || a.height != r.height)
        throw MetricsError("images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                           " against a reference of " + std::to_string(r.width) + "x" + std::to_string(r.height));
    if (a.width <= 0 || a.height <= 0) throw MetricsError("cannot compare empty images");
    const std::size_t n = std::size_t(a.width) * std::size_t(a.height) * 3;
    if (a.rgb.size() != n || r.rgb.size() != n) throw MetricsError("image storage does not match its size");
}

bool finite3(const float* p)
{
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// Luminance per pixel; a pixel with a non-finite channel in either image is 0 in both (see metrics.h).
void luminancePair(const Image& a, const Image& r, std::vector<double>& la, std::vector<double>& lr)
{
    const std::size_t n = std::size_t(a.width) * std::size_t(a.height);
    la.assign(n, 0.0);
    lr.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        const float* pa = &a.rgb[3 * i];
        const float* pr = &r.rgb[3 * i];
        if (!finite3(pa) || !finite3(pr)) continue;
        la[i] = luminance({pa[0], pa[1], pa[2]});
        lr[i] = luminance({pr[0], pr[1], pr[2]});
    }
}

// Separable Gaussian blur (11 taps, sigma 1.5) with the window clipped at the border and renormalised.
std::vector<double> gaussianBlur(const std::vector<double>& src, int w, int h)
{
    constexpr int kRadius = 5;
    std::array<double, 2 * kRadius + 1> taps{};
    for (int i = -kRadius; i <= kRadius; ++i)
        taps[std::size_t(i + kRadius)] = std::exp(-double(i * i) / (2.0 * 1.5 * 1.5));
    std::vector<double> tmp(src.size()), dst(src.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0.0, wsum = 0.0;
            for (int i = std::max(-kRadius, -x); i <= std::min(kRadius, w - 1 - x); ++i) {
                sum += taps[std::size_t(i + kRadius)] * src[std::size_t(y) * std::size_t(w) + std::size_t(x + i)];
                wsum += taps[std::size_t(i + kRadius)];
            }
            tmp[std::size_t(y) * std::size_t(w) + std::size_t(x)] = sum / wsum;
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0.0, wsum = 0.0;
            for (int i = std::max(-kRadius, -y); i <= std::min(kRadius, h - 1 - y); ++i) {
                sum += taps[std::size_t(i + kRadius)] * tmp[std::size_t(y + i) * std::size_t(w) + std::size_t(x)];
                wsum += taps[std::size_t(i + kRadius)];
            }
            dst[std::size_t(y) * std::size_t(w) + std::size_t(x)] = sum / wsum;
        }
    return dst;
}

double ssimChecked(const Image& a, const Image& r)
{
    std::vector<double> la, lr;
    luminancePair(a, r, la, lr);
    // The dynamic range L: the 99th percentile of the reference's luminance, its maximum if that is 0,
    // 1 if everything is black (metrics.h says why not the maximum).
    std::vector<double> sorted = lr;
    const auto rank = sorted.begin() + std::ptrdiff_t(0.99 * double(sorted.size() - 1));
    std::nth_element(sorted.begin(), rank, sorted.end());
    double range = *rank;
    if (!(range > 0.0)) range = *std::max_element(lr.begin(), lr.end());
    if (!(range > 0.0)) range = 1.0;
    const double c1 = (0.01 * range) * (0.01 * range);
    const double c2 = (0.03 * range) * (0.03 * range);

    const int w = a.width, h = a.height;
    std::vector<double> aa(la.size()), rr(la.size()), ar(la.size());
    for (std::size_t i = 0; i < la.size(); ++i) {
        aa[i] = la[i] * la[i];
        rr[i] = lr[i] * lr[i];
        ar[i] = la[i] * lr[i];
    }
    const std::vector<double> muA = gaussianBlur(la, w, h), muR = gaussianBlur(lr, w, h);
    const std::vector<double> eAA = gaussianBlur(aa, w, h), eRR = gaussianBlur(rr, w, h), eAR = gaussianBlur(ar, w, h);
    double sum = 0.0;
    for (std::size_t i = 0; i < la.size(); ++i) {
        const double varA = eAA[i] - muA[i] * muA[i];
        const double varR = eRR[i] - muR[i] * muR[i];
        const double cov = eAR[i] - muA[i] * muR[i];
        // Wang et al. 2004, Eq. 13.
        sum += ((2.0 * muA[i] * muR[i] + c1) * (2.0 * cov + c2)) /
               ((muA[i] * muA[i] + muR[i] * muR[i] + c1) * (varA + varR + c2));
    }
    return sum / double(la.size());
}

// The per-value sums behind every figure except SSIM.
ImageMetrics pointwise(const Image& a, const Image& r, double eps)
{
    ImageMetrics m;
    m.width = a.width;
    m.height = a.height;
    double se = 0.0, rel = 0.0, ae = 0.0, sumA = 0.0, sumR = 0.0, maxErr = 0.0;
    std::array<double, 3> channelSumA{}, channelSumR{};
    std::array<std::size_t, 3> channelCount{};
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        const double va = a.rgb[i], vr = r.rgb[i];
        const bool fa = std::isfinite(va), fr = std::isfinite(vr);
        m.nonFiniteImage += fa ? 0 : 1;
        m.nonFiniteReference += fr ? 0 : 1;
        if (!fa || !fr) continue;
        const double d = va - vr;
        se += d * d;
        rel += d * d / (vr * vr + eps);
        ae += std::abs(d);
        maxErr = std::max(maxErr, std::abs(d));
        sumA += va;
        sumR += vr;
        channelSumA[i % 3] += va;
        channelSumR[i % 3] += vr;
        ++channelCount[i % 3];
        ++m.valuesCompared;
    }
    const double n = m.valuesCompared > 0 ? double(m.valuesCompared) : 1.0;
    m.rmse = std::sqrt(se / n);
    m.relativeMse = rel / n;
    m.mae = ae / n;
    m.maxError = maxErr;
    m.meanImage = sumA / n;
    m.meanReference = sumR / n;
    if (m.meanReference > 0.0)
        m.relativeRmse = m.rmse / m.meanReference;
    else
        m.relativeRmse = m.rmse == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
    if (m.valuesCompared == 0) m.meanImage = m.meanReference = std::numeric_limits<double>::quiet_NaN();
    for (int c = 0; c < 3; ++c) {
        const bool any = channelCount[c] > 0;
        m.channelMeanImage[c] =
            any ? channelSumA[c] / double(channelCount[c]) : std::numeric_limits<double>::quiet_NaN();
        m.channelMeanReference[c] =
            any ? channelSumR[c] / double(channelCount[c]) : std::numeric_limits<double>::quiet_NaN();
    }
    if (!m.allFinite()) {
        // A renderer that writes NaN must never look flawless: every error figure is infinite.
        const double inf = std::numeric_limits<double>::infinity();
        m.rmse = m.relativeRmse = m.relativeMse = m.mae = m.maxError = inf;
    }
    return m;
}

// The heat-map ramp: stops at log10(e) = -4 (black), -3 (blue), -2.25 (cyan), -1.5 (green),
// -0.75 (yellow), 0 (red), 1 (white).
glm::vec3 ramp(double e)
{
    static const std::array<std::pair<double, glm::vec3>, 7> kStops = {{
        {-4.0, {0.0f, 0.0f, 0.0f}},
        {-3.0, {0.0f, 0.0f, 1.0f}},
        {-2.25, {0.0f, 1.0f, 1.0f}},
        {-1.5, {0.0f, 1.0f, 0.0f}},
        {-0.75, {1.0f, 1.0f, 0.0f}},
        {0.0, {1.0f, 0.0f, 0.0f}},
        {1.0, {1.0f, 1.0f, 1.0f}},
    }};
    const double t = e > 0.0 ? std::log10(e) : -std::numeric_limits<double>::infinity();
    if (t <= kStops.front().first) return kStops.front().second;
    for (std::size_t i = 1; i < kStops.size(); ++i)
        if (t <= kStops[i].first) {
            const float s = float((t - kStops[i - 1].first) / (kStops[i].first - kStops[i - 1].first));
            return glm::mix(kStops[i - 1].second, kStops[i].second, s);
        }
    return kStops.back().second;
}

} // namespace

ImageMetrics compareImages(const Image& a, const Image& reference, double relativeMseEpsilon)
{
    checkSizes(a, reference);
    ImageMetrics m = pointwise(a, reference, relativeMseEpsilon);
    m.ssim = m.allFinite() ? ssimChecked(a, reference) : 0.0;
    return m;
}

double rmse(const Image& a, const Image& reference)
{
    checkSizes(a, reference);
    return pointwise(a, reference, kRelativeMseEpsilon).rmse;
}

double relativeRmse(const Image& a, const Image& reference)
{
    checkSizes(a, reference);
    return pointwise(a, reference, kRelativeMseEpsilon).relativeRmse;
}

double errorFlicker(const Image& a, const Image& refA, const Image& b, const Image& refB)
{
    checkSizes(a, refA);
    checkSizes(b, refB);
    checkSizes(a, b);
    double sumSq = 0.0, sumRef = 0.0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        const double change = (double(a.rgb[i]) - refA.rgb[i]) - (double(b.rgb[i]) - refB.rgb[i]);
        if (!std::isfinite(change) || !std::isfinite(double(refA.rgb[i]) + refB.rgb[i]))
            return std::numeric_limits<double>::infinity();
        sumSq += change * change;
        sumRef += 0.5 * (double(refA.rgb[i]) + refB.rgb[i]);
    }
    const double n = double(a.rgb.size());
    if (sumSq == 0.0) return 0.0;
    if (sumRef <= 0.0) return std::numeric_limits<double>::infinity();
    return std::sqrt(sumSq / n) / (sumRef / n);
}

double relativeMse(const Image& a, const Image& reference, double epsilon)
{
    checkSizes(a, reference);
    return pointwise(a, reference, epsilon).relativeMse;
}

double meanAbsoluteError(const Image& a, const Image& reference)
{
    checkSizes(a, reference);
    return pointwise(a, reference, kRelativeMseEpsilon).mae;
}

double maxError(const Image& a, const Image& reference)
{
    checkSizes(a, reference);
    return pointwise(a, reference, kRelativeMseEpsilon).maxError;
}

double ssim(const Image& a, const Image& reference)
{
    checkSizes(a, reference);
    return ssimChecked(a, reference);
}

Image boxDownsample(const Image& image, int width, int height)
{
    if (width < 1 || height < 1 || image.width % width != 0 || image.height % height != 0)
        throw std::invalid_argument("box downsampling: " + std::to_string(width) + "x" + std::to_string(height) +
                                    " does not divide " + std::to_string(image.width) + "x" +
                                    std::to_string(image.height));
    const int fx = image.width / width, fy = image.height / height;
    Image out(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            glm::dvec3 sum(0.0);
            for (int j = 0; j < fy; ++j)
                for (int i = 0; i < fx; ++i) sum += glm::dvec3(image.at(x * fx + i, y * fy + j));
            out.set(x, y, glm::vec3(sum / double(fx * fy)));
        }
    return out;
}

Image errorHeatmap(const Image& a, const Image& reference)
{
    checkSizes(a, reference);
    const std::size_t n = std::size_t(a.width) * std::size_t(a.height);
    double sumRef = 0.0;
    std::size_t finitePixels = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const float* pr = &reference.rgb[3 * i];
        if (!finite3(pr)) continue;
        sumRef += double(pr[0]) + double(pr[1]) + double(pr[2]);
        ++finitePixels;
    }
    const double meanRef = finitePixels > 0 ? sumRef / double(finitePixels) : 0.0;
    const double eps = meanRef > 0.0 ? 0.01 * meanRef : 1e-6;
    Image out(a.width, a.height);
    for (std::size_t i = 0; i < n; ++i) {
        const float* pa = &a.rgb[3 * i];
        const float* pr = &reference.rgb[3 * i];
        glm::vec3 c;
        if (!finite3(pa) || !finite3(pr)) {
            c = {1.0f, 0.0f, 1.0f};
        } else {
            double diff = 0.0, ref = 0.0;
            for (int k = 0; k < 3; ++k) {
                diff += std::abs(double(pa[k]) - double(pr[k]));
                ref += double(pr[k]);
            }
            c = ramp(diff / (std::abs(ref) + eps));
        }
        out.rgb[3 * i] = c.x;
        out.rgb[3 * i + 1] = c.y;
        out.rgb[3 * i + 2] = c.z;
    }
    return out;
}

std::vector<bool> blocksAbove(const Image& image, int block, float limit)
{
    const int w = image.width / block, h = image.height / block;
    std::vector<bool> above(std::size_t(w) * std::size_t(h), false), mask(above.size(), false);
    for (int y = 0; y < h * block; ++y)
        for (int x = 0; x < w * block; ++x)
            if (luminance(image.at(x, y)) > limit) above[std::size_t(y / block) * w + std::size_t(x / block)] = true;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!above[std::size_t(y) * w + x]) continue;
            for (int j = std::max(y - 1, 0); j <= std::min(y + 1, h - 1); ++j)
                for (int i = std::max(x - 1, 0); i <= std::min(x + 1, w - 1); ++i) mask[std::size_t(j) * w + i] = true;
        }
    return mask;
}

Image blanked(Image image, const std::vector<bool>& mask)
{
    for (std::size_t i = 0; i < mask.size(); ++i)
        if (mask[i]) image.rgb[3 * i] = image.rgb[3 * i + 1] = image.rgb[3 * i + 2] = 0.0f;
    return image;
}

} // namespace bounce::core
