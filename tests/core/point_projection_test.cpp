// The closed forms of importance-driven point projection (core/point_projection.h): the hemi-octahedral
// map (Eq. 2) is one to one and its texel solid angles sum to 2 pi; Eq. 5 never exceeds 2 pi cos theta;
// the carry rule gives exactly N_s samples whatever the importances (zeros, a tiny p_k, NaN), each
// cluster within two of its share.
#include <cmath>
#include <numeric>
#include <set>

#include <gtest/gtest.h>

#include "core/point_projection.h"
#include "core/sampling.h"

namespace bounce {
namespace {

constexpr double kTwoPi = 6.283185307179586;

TEST(HemiOct, RoundTripsAndIsOneToOne)
{
    core::Pcg32 rng(3);
    for (int k = 0; k < 10000; ++k) {
        const glm::vec3 w = core::sampleCosineHemisphere(rng.next2());
        const glm::vec2 t = core::hemiOctEncode(w);
        ASSERT_GE(t.x, -1e-6f);
        ASSERT_LE(t.x, 1.0f + 1e-6f);
        ASSERT_GE(t.y, -1e-6f);
        ASSERT_LE(t.y, 1.0f + 1e-6f);
        EXPECT_LT(glm::length(core::hemiOctDecode(t) - w), 1e-5f);
    }
    // Every texel centre decodes to a direction that encodes back into the same texel.
    constexpr int r = 32;
    std::set<int> texels;
    for (int y = 0; y < r; ++y)
        for (int x = 0; x < r; ++x) {
            const glm::vec2 t = core::hemiOctEncode(core::hemiOctDecode((glm::vec2(x, y) + 0.5f) / float(r)));
            const glm::ivec2 c = glm::ivec2(glm::floor(t * float(r)));
            EXPECT_EQ(c, glm::ivec2(x, y));
            texels.insert(c.y * r + c.x);
        }
    EXPECT_EQ(int(texels.size()), r * r);
    // The normal goes to the centre; the horizon to the square's border.
    EXPECT_LT(glm::length(core::hemiOctEncode({0, 0, 1}) - glm::vec2(0.5f)), 1e-6f);
    EXPECT_LT(glm::length(core::hemiOctEncode({1, 0, 0}) - glm::vec2(0.0f)), 1e-6f);
}

TEST(HemiOct, TexelSolidAnglesSumToTwoPi)
{
    for (int r : {1, 3, 32}) {
        const std::vector<float> omega = core::hemiOctTexelSolidAngles(r);
        double sum = 0.0;
        for (float o : omega) {
            EXPECT_GT(o, 0.0f);
            sum += o;
        }
        EXPECT_NEAR(sum, kTwoPi, 1e-5) << r;
    }
    // Against a Monte Carlo count: texel solid angle = 2 pi x the share of uniform directions it gets.
    constexpr int r = 8;
    const std::vector<float> omega = core::hemiOctTexelSolidAngles(r);
    std::vector<int> hits(r * r, 0);
    core::Pcg32 rng(5);
    constexpr int n = 400000;
    for (int k = 0; k < n; ++k) {
        const glm::vec2 u = rng.next2();
        const float z = u.x, phi = float(kTwoPi) * u.y, s = std::sqrt(1.0f - z * z);
        const glm::vec2 t = core::hemiOctEncode({s * std::cos(phi), s * std::sin(phi), z});
        const glm::ivec2 c = glm::clamp(glm::ivec2(glm::floor(t * float(r))), glm::ivec2(0), glm::ivec2(r - 1));
        ++hits[c.y * r + c.x];
    }
    for (int i = 0; i < r * r; ++i) EXPECT_NEAR(omega[i], kTwoPi * hits[i] / n, 0.01 * kTwoPi / (r * r) + 0.004) << i;
}

TEST(RobustSolidAngle, NeverExceedsTwoPiCosAndMatchesEq3FarAway)
{
    for (float a : {1e-8f, 1e-4f, 1.0f, 1e4f})
        for (float c : {0.0f, 0.3f, 1.0f, -0.7f})
            for (float d2 : {0.0f, 1e-12f, 1e-4f, 1.0f, 1e6f}) {
                const float o = core::robustSolidAngle(a, c, d2);
                EXPECT_TRUE(std::isfinite(o));
                EXPECT_LE(o, float(kTwoPi) * std::abs(c) * (1.0f + 1e-6f));
                EXPECT_GE(o, 0.0f);
            }
    EXPECT_NEAR(core::robustSolidAngle(1e-4f, 0.5f, 4.0f), 1e-4f * 0.5f / 4.0f, 1e-9f);
}

TEST(Carry, SumsToExactlyNsWhateverTheImportance)
{
    core::Pcg32 rng(11);
    for (int trial = 0; trial < 300; ++trial) {
        const int k = 1 + int(rng.nextBounded(600));
        std::vector<float> p(k), u(k);
        for (int i = 0; i < k; ++i) {
            const float r = rng.nextFloat();
            p[i] = r < 0.2f ? 0.0f : (r < 0.25f ? 1e-30f : (r < 0.27f ? NAN : rng.nextFloat() * 1e3f));
            u[i] = rng.nextFloat();
        }
        const std::uint32_t ns = rng.nextBounded(5000);
        const std::vector<std::uint32_t> n = core::carryAllocate(p, ns, u);
        EXPECT_EQ(std::accumulate(n.begin(), n.end(), std::uint64_t(0)), std::uint64_t(ns)) << trial;
        for (int i = 0; i + 1 < k; ++i)
            if (!(p[i] > 0.0f) || !std::isfinite(p[i])) {
                EXPECT_LE(n[i], 1u) << "a cluster of no importance";
            }
    }
}

TEST(Carry, AllZeroFallsBackToUniformAndCountsStayNearTheirShare)
{
    std::vector<float> zero(512, 0.0f), u(512, 0.5f);
    const std::vector<std::uint32_t> n = core::carryAllocate(zero, 2048, u);
    for (std::uint32_t c : n) EXPECT_EQ(c, 4u);
    // Each count stays within two of N_s p_k: the carry moves at most one sample (either way) from one
    // cluster to the next (§3.2's rule is not unbiased per cluster, only in total).
    const std::vector<float> p = {0.1f, 2.5f, 0.0f, 0.4f, 7.0f};
    core::Pcg32 rng(2);
    for (int t = 0; t < 2000; ++t) {
        std::vector<float> r(p.size());
        for (float& x : r) x = rng.nextFloat();
        const auto c = core::carryAllocate(p, 7, r);
        for (std::size_t i = 0; i < p.size(); ++i) EXPECT_LE(std::abs(double(c[i]) - 7.0 * p[i] / 10.0), 2.0) << i;
    }
}

} // namespace
} // namespace bounce
