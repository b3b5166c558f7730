#include "core/point_projection.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bounce::core {

glm::vec2 hemiOctEncode(const glm::vec3& w)
{
    const float l1 = std::abs(w.x) + std::abs(w.y) + std::abs(w.z);
    const glm::vec3 p = l1 > 0.0f ? w / l1 : glm::vec3(0.0f, 0.0f, 1.0f);
    return {0.5f * (1.0f - p.x + p.y), 0.5f * (1.0f - p.x - p.y)};
}

glm::vec3 hemiOctDecode(const glm::vec2& t)
{
    const float x = 1.0f - t.x - t.y, y = t.x - t.y;
    const float z = std::max(0.0f, 1.0f - std::abs(x) - std::abs(y));
    return glm::normalize(glm::vec3(x, y, z));
}

namespace {

// Van Oosterom & Strackee 1983: the solid angle of the spherical triangle of unit vectors a, b, c.
double triangleSolidAngle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c)
{
    const double num = std::abs(glm::dot(a, glm::cross(b, c)));
    const double den = 1.0 + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a);
    return 2.0 * std::atan2(num, den);
}

glm::dvec3 decodeD(double tx, double ty)
{
    const double x = 1.0 - tx - ty, y = tx - ty;
    const double z = std::max(0.0, 1.0 - std::abs(x) - std::abs(y));
    return glm::normalize(glm::dvec3(x, y, z));
}

} // namespace

std::vector<float> hemiOctTexelSolidAngles(int resolution)
{
    if (resolution < 1) throw std::invalid_argument("hemi-octahedral buffer of no texels");
    std::vector<float> out(std::size_t(resolution) * resolution);
    const double r = resolution;
    for (int y = 0; y < resolution; ++y)
        for (int x = 0; x < resolution; ++x) {
            const glm::dvec3 c = decodeD((x + 0.5) / r, (y + 0.5) / r);
            const glm::dvec3 k[4] = {decodeD(x / r, y / r), decodeD((x + 1) / r, y / r),
                                     decodeD((x + 1) / r, (y + 1) / r), decodeD(x / r, (y + 1) / r)};
            double sum = 0.0;
            for (int e = 0; e < 4; ++e) sum += triangleSolidAngle(c, k[e], k[(e + 1) % 4]);
            out[std::size_t(y) * resolution + x] = float(sum);
        }
    return out;
}

float robustSolidAngle(float areaM2, float cosThetaS, float distance2)
{
    constexpr float kTwoPi = 6.28318530717958647692f;
    const float den = areaM2 + kTwoPi * distance2;
    return den > 0.0f ? kTwoPi * areaM2 * std::abs(cosThetaS) / den : kTwoPi * std::abs(cosThetaS);
}

float pointImportance(float cosThetaP, float cosThetaS, float distance2, float areaM2)
{
    if (!(distance2 > 0.0f)) return 0.0f;
    return std::max(cosThetaP, 0.0f) * std::abs(cosThetaS) / distance2 * areaM2;
}

std::vector<std::uint32_t> carryAllocate(const std::vector<float>& importance, std::uint32_t total,
                                         const std::vector<float>& random)
{
    const std::size_t k = importance.size();
    std::vector<std::uint32_t> n(k, 0);
    if (k == 0) return n;
    double sum = 0.0;
    for (float p : importance)
        if (std::isfinite(p) && p > 0.0f) sum += p;
    float carry = 0.0f;
    std::uint32_t assigned = 0;
    for (std::size_t c = 0; c + 1 < k; ++c) {
        const float p =
            sum > 0.0 ? ((std::isfinite(importance[c]) && importance[c] > 0.0f) ? float(importance[c] / sum) : 0.0f)
                      : 1.0f / float(k);
        float f = float(total) * p + carry;
        auto nk = std::uint32_t(std::max(f, 0.0f));
        f -= float(nk);
        if (random[c] < f) {
            ++nk;
            carry = f - 1.0f;
        } else {
            carry = f;
        }
        nk = std::min(nk, total - assigned);
        n[c] = nk;
        assigned += nk;
    }
    n[k - 1] = total - assigned;
    return n;
}

} // namespace bounce::core
