#include "core/brdf_warp.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/brdf.h"

namespace bounce::core {

namespace {

constexpr int kSubsamples = 8; // per bin side: the midpoint rule on 8 x 8 points per bin

constexpr double kHalfPi = 1.57079632679489661923;

// The table's density over (a, v): f(w) (pi / 2) s^2, with wx = sin(pi a / 2), s = cos(pi a / 2), wy = v s.
template <class F>
std::vector<float> tabulate(int bins, F f)
{
    std::vector<double> mass(std::size_t(bins) * bins, 0.0);
    double total = 0.0;
    for (int i = 0; i < bins; ++i)
        for (int j = 0; j < bins; ++j) {
            double sum = 0.0;
            for (int a = 0; a < kSubsamples; ++a)
                for (int b = 0; b < kSubsamples; ++b) {
                    const double angle = kHalfPi * (-1.0 + 2.0 * (i + (a + 0.5) / kSubsamples) / bins);
                    const double v = -1.0 + 2.0 * (j + (b + 0.5) / kSubsamples) / bins;
                    const double wx = std::sin(angle), s = std::cos(angle);
                    const double wy = v * s;
                    const double wz = std::sqrt(std::max(0.0, 1.0 - wx * wx - wy * wy));
                    sum += f(glm::vec3(float(wx), float(wy), float(wz))) * kHalfPi * s * s;
                }
            mass[std::size_t(i) * bins + j] = sum;
            total += sum;
        }
    std::vector<float> out(mass.size());
    for (std::size_t k = 0; k < mass.size(); ++k)
        out[k] = total > 0.0 ? float(mass[k] / total) : 1.0f / float(mass.size());
    return out;
}

} // namespace

int BrdfWarpTables::ggxTable(float cosThetaO, float alpha) const
{
    const int nc = int(this->cosThetaO.size());
    int ic = int(std::clamp(cosThetaO, 0.0f, 1.0f) * float(nc));
    ic = std::clamp(ic, 0, nc - 1);
    int ia = 0;
    const float la = std::log(std::max(alpha, 1e-6f));
    for (int k = 1; k < int(alphas.size()); ++k)
        if (std::abs(std::log(alphas[k]) - la) < std::abs(std::log(alphas[ia]) - la)) ia = k;
    return 1 + ia * nc + ic;
}

BrdfWarpTables makeBrdfWarpTables(int bins, int cosSteps, const std::vector<float>& alphas)
{
    if (bins < 1 || cosSteps < 1 || alphas.empty()) throw std::invalid_argument("empty BRDF warp table");
    BrdfWarpTables t;
    t.bins = bins;
    t.alphas = alphas;
    for (int c = 0; c < cosSteps; ++c) t.cosThetaO.push_back((float(c) + 0.5f) / float(cosSteps));
    const std::vector<float> lambert = tabulate(bins, [](const glm::vec3&) { return 1.0 / 3.14159265358979323846; });
    t.mass = lambert;
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    for (float alpha : alphas)
        for (float cosO : t.cosThetaO) {
            const glm::vec3 wo(std::sqrt(std::max(0.0f, 1.0f - cosO * cosO)), 0.0f, cosO);
            const std::vector<float> m = tabulate(bins, [&](const glm::vec3& wi) -> double {
                if (wi.z <= 0.0f) return 0.0;
                const glm::vec3 h = glm::normalize(wo + wi);
                return double(ggxD(std::max(glm::dot(n, h), 0.0f), alpha)) * smithVisibility(wi.z, wo.z, alpha);
            });
            t.mass.insert(t.mass.end(), m.begin(), m.end());
        }
    return t;
}

std::vector<float> mixWarpMass(const BrdfWarpTables& tables, float specularShare, int ggx)
{
    const std::size_t k2 = std::size_t(tables.bins) * tables.bins;
    std::vector<float> out(k2);
    for (std::size_t k = 0; k < k2; ++k)
        out[k] = (1.0f - specularShare) * tables.mass[k] + specularShare * tables.mass[std::size_t(ggx) * k2 + k];
    return out;
}

float warpSpecularShare(const glm::vec3& diffuse, const glm::vec3& f0, float weight, float cosThetaO)
{
    if (weight <= 0.0f) return 0.0f;
    const float wF = weight * luminance(fresnelSchlick(f0, cosThetaO));
    const float d = luminance(diffuse) * std::max(0.0f, 1.0f - wF);
    if (d <= 0.0f) return 1.0f;
    return wF / (wF + d);
}

BrdfWarp::BrdfWarp(const std::vector<float>& mass, int bins) : bins_(bins), mass_(mass)
{
    if (bins < 1 || mass.size() != std::size_t(bins) * bins) throw std::invalid_argument("BRDF warp: bad table");
    marginal_.assign(std::size_t(bins) + 1, 0.0f);
    rows_.assign(std::size_t(bins) * (bins + 1), 0.0f);
    std::vector<double> rowMass(bins, 0.0);
    double total = 0.0;
    for (int i = 0; i < bins; ++i) {
        double run = 0.0;
        for (int j = 0; j < bins; ++j) run += mass_[std::size_t(i) * bins + j];
        rowMass[i] = run;
        total += run;
        double acc = 0.0;
        for (int j = 0; j <= bins; ++j) {
            rows_[std::size_t(i) * (bins + 1) + j] = run > 0.0 ? float(acc / run) : float(j) / float(bins);
            if (j < bins) acc += mass_[std::size_t(i) * bins + j];
        }
        rows_[std::size_t(i) * (bins + 1) + bins] = 1.0f;
    }
    double acc = 0.0;
    for (int i = 0; i <= bins; ++i) {
        marginal_[i] = total > 0.0 ? float(acc / total) : float(i) / float(bins);
        if (i < bins) acc += rowMass[i];
    }
    marginal_[bins] = 1.0f;
    // The density uses the mass normalised to the total (the CDFs are normalised anyway).
    if (total > 0.0)
        for (float& m : mass_) m = float(m / total);
}

namespace {

// The bin k of a CDF with cdf[k] <= u < cdf[k + 1] (bins of zero width are never chosen), and where u lies in it.
int searchCdf(const float* cdf, int bins, float u, float& frac)
{
    int lo = 0, hi = bins;
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        if (cdf[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    const float width = cdf[lo + 1] - cdf[lo];
    frac = width > 0.0f ? std::clamp((u - cdf[lo]) / width, 0.0f, 1.0f) : 0.5f;
    return lo;
}

} // namespace

glm::vec3 BrdfWarp::toDirection(const glm::vec2& u) const
{
    float fx = 0.0f, fy = 0.0f;
    const int i = searchCdf(marginal_.data(), bins_, u.x, fx);
    const int j = searchCdf(rows_.data() + std::size_t(i) * (bins_ + 1), bins_, u.y, fy);
    const float angle = 1.57079632679489661923f * (-1.0f + 2.0f * (float(i) + fx) / float(bins_));
    const float v = -1.0f + 2.0f * (float(j) + fy) / float(bins_);
    const float wx = std::sin(angle), s = std::cos(angle);
    const float wy = v * s;
    return {wx, wy, std::sqrt(std::max(0.0f, 1.0f - wx * wx - wy * wy))};
}

glm::ivec2 BrdfWarp::binOf(const glm::vec3& w, glm::vec2& frac) const
{
    // s = cos(pi a / 2) from w's other components: asin(wx) loses its precision near the rim.
    const float s = std::sqrt(w.y * w.y + std::max(w.z, 0.0f) * std::max(w.z, 0.0f));
    const float v = s > 0.0f ? std::clamp(w.y / s, -1.0f, 1.0f) : 0.0f;
    const float a = std::atan2(w.x, s) / 1.57079632679489661923f;
    const float tx = (a + 1.0f) * 0.5f * float(bins_), ty = (v + 1.0f) * 0.5f * float(bins_);
    const int i = std::clamp(int(std::floor(tx)), 0, bins_ - 1), j = std::clamp(int(std::floor(ty)), 0, bins_ - 1);
    frac = glm::vec2(std::clamp(tx - float(i), 0.0f, 1.0f), std::clamp(ty - float(j), 0.0f, 1.0f));
    return {i, j};
}

glm::vec2 BrdfWarp::toUnit(const glm::vec3& w) const
{
    glm::vec2 f;
    const glm::ivec2 b = binOf(w, f);
    const float x = marginal_[b.x] + f.x * (marginal_[b.x + 1] - marginal_[b.x]);
    const float* row = rows_.data() + std::size_t(b.x) * (bins_ + 1);
    const float y = row[b.y] + f.y * (row[b.y + 1] - row[b.y]);
    return {x, y};
}

float BrdfWarp::pdf(const glm::vec3& w) const
{
    glm::vec2 f;
    const glm::ivec2 b = binOf(w, f);
    const float q = mass_[std::size_t(b.x) * bins_ + b.y] * float(bins_ * bins_) * 0.25f;
    const float s2 = w.y * w.y + std::max(w.z, 0.0f) * std::max(w.z, 0.0f);
    return s2 > 0.0f ? q * std::max(w.z, 0.0f) / (1.57079632679489661923f * s2) : 0.0f;
}

float BrdfWarp::cosineSolidAngle(const glm::vec3& w, int resolution) const
{
    glm::vec2 f;
    const glm::ivec2 b = binOf(w, f);
    const float q = mass_[std::size_t(b.x) * bins_ + b.y] * float(bins_ * bins_) * 0.25f;
    const float s2 = w.y * w.y + std::max(w.z, 0.0f) * std::max(w.z, 0.0f);
    return q > 0.0f ? 1.57079632679489661923f * s2 / (float(resolution * resolution) * q) : 0.0f;
}

float BrdfWarp::pixelSolidAngle(const glm::vec3& w, int resolution) const
{
    const float p = pdf(w);
    return p > 0.0f ? 1.0f / (float(resolution * resolution) * p) : INFINITY;
}

glm::vec2 BrdfWarp::cellSample(glm::ivec2 cell, glm::vec2 jitter, int resolution)
{
    return (glm::vec2(cell) + 0.5f + jitter) / float(resolution);
}

glm::ivec2 BrdfWarp::cellOf(glm::vec2 u, int resolution)
{
    return glm::clamp(glm::ivec2(glm::floor(u * float(resolution))), glm::ivec2(0), glm::ivec2(resolution - 1));
}

} // namespace bounce::core
