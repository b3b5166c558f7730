// core/sampling.h: the generator against O'Neill's published output, jump-ahead, and each warp against
// its closed-form moments (means of known integrals, with tolerances of 5 standard errors).
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/sampling.h"
#include "core/scene.h"

namespace {

using namespace bounce::core;

constexpr int kN = 200000;

// 5 standard errors of a mean of kN samples of a quantity with variance `var`.
double tol(double var)
{
    return 5.0 * std::sqrt(var / kN);
}

TEST(Pcg32, MatchesReferenceOutput)
{
    // pcg32-demo of the PCG reference implementation, seeded with initstate 42 and initseq 54.
    Pcg32 rng(42u, 54u);
    const std::uint32_t expected[] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u, 0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
    for (std::uint32_t e : expected) EXPECT_EQ(rng.nextU32(), e);
}

TEST(Pcg32, AdvanceMatchesStepping)
{
    Pcg32 a(7, 3), b(7, 3);
    for (int i = 0; i < 1000; ++i) a.nextU32();
    b.advance(1000);
    EXPECT_TRUE(a == b);
    b.advance(-1000);
    EXPECT_TRUE(b == Pcg32(7, 3));
}

TEST(Pcg32, StreamsAndSeedsDiffer)
{
    Pcg32 a(1, 1), b(1, 2), c(2, 1);
    int same = 0;
    for (int i = 0; i < 100; ++i) {
        const std::uint32_t x = a.nextU32(), y = b.nextU32(), z = c.nextU32();
        same += (x == y) + (x == z);
    }
    EXPECT_LE(same, 1);
}

TEST(Pcg32, FloatsAreInUnitIntervalAndUniform)
{
    Pcg32 rng(123, 0);
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < kN; ++i) {
        const float u = rng.nextFloat();
        ASSERT_GE(u, 0.0f);
        ASSERT_LT(u, 1.0f);
        sum += u;
        sum2 += double(u) * u;
    }
    EXPECT_NEAR(sum / kN, 0.5, tol(1.0 / 12.0));
    EXPECT_NEAR(sum2 / kN, 1.0 / 3.0, tol(4.0 / 45.0));
    std::vector<int> counts(7, 0);
    for (int i = 0; i < 70000; ++i) ++counts[rng.nextBounded(7)];
    for (int c : counts) EXPECT_NEAR(c, 10000, 5 * std::sqrt(10000.0));
}

TEST(Frame, OrthonormalEverywhereIncludingNearMinusZ)
{
    Pcg32 rng(5, 0);
    std::vector<glm::vec3> normals = {
        {0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}, glm::normalize(glm::vec3(1e-7f, 0, -1))};
    for (int i = 0; i < 10000; ++i) normals.push_back(sampleUniformSphere(rng.next2()));
    for (const glm::vec3& n : normals) {
        const Frame f = Frame::fromNormal(n);
        EXPECT_NEAR(glm::length(f.t), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::length(f.b), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(f.t, f.b), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(f.t, n), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(f.b, n), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::length(glm::cross(f.t, f.b) - n), 0.0f, 1e-5f); // right-handed
        const glm::vec3 v = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
        EXPECT_NEAR(glm::length(f.toWorld(f.toLocal(v)) - v), 0.0f, 1e-5f);
    }
}

TEST(Warps, CosineHemisphereMoments)
{
    // pdf cos/pi: E[cos] = 2/3, E[cos^2] = 1/2, E[x] = E[y] = 0.
    Pcg32 rng(9, 0);
    double z = 0.0, z2 = 0.0, x = 0.0;
    for (int i = 0; i < kN; ++i) {
        const glm::vec3 d = sampleCosineHemisphere(rng.next2());
        ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
        ASSERT_GE(d.z, 0.0f);
        z += d.z;
        z2 += double(d.z) * d.z;
        x += d.x;
    }
    EXPECT_NEAR(z / kN, 2.0 / 3.0, tol(0.5 - 4.0 / 9.0));
    EXPECT_NEAR(z2 / kN, 0.5, tol(1.0 / 3.0 - 0.25));
    EXPECT_NEAR(x / kN, 0.0, tol(0.25));
    EXPECT_FLOAT_EQ(cosineHemispherePdf(0.5f), 0.5f / kPi);
    EXPECT_EQ(cosineHemispherePdf(-0.1f), 0.0f);
}

TEST(Warps, UniformSphereMoments)
{
    Pcg32 rng(10, 0);
    double z = 0.0, z2 = 0.0, y = 0.0;
    for (int i = 0; i < kN; ++i) {
        const glm::vec3 d = sampleUniformSphere(rng.next2());
        ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
        z += d.z;
        z2 += double(d.z) * d.z;
        y += d.y;
    }
    EXPECT_NEAR(z / kN, 0.0, tol(1.0 / 3.0));
    EXPECT_NEAR(z2 / kN, 1.0 / 3.0, tol(1.0 / 5.0 - 1.0 / 9.0));
    EXPECT_NEAR(y / kN, 0.0, tol(1.0 / 3.0));
    EXPECT_FLOAT_EQ(uniformSpherePdf(), 1.0f / (4.0f * kPi));
}

TEST(Warps, UniformConeMoments)
{
    // cos(theta) is uniform on [c, 1]: mean (1 + c) / 2, variance (1 - c)^2 / 12.
    Pcg32 rng(11, 0);
    for (float c : {-0.5f, 0.0f, 0.7071f, 0.99f}) {
        double z = 0.0;
        for (int i = 0; i < kN; ++i) {
            const glm::vec3 d = sampleUniformCone(rng.next2(), c);
            ASSERT_GE(d.z, c - 1e-6f);
            ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
            z += d.z;
        }
        EXPECT_NEAR(z / kN, 0.5 * (1.0 + c), tol((1.0 - c) * (1.0 - c) / 12.0)) << c;
        EXPECT_NEAR(uniformConePdf(c), 1.0 / (2.0 * kPi * (1.0 - c)), 1e-6 / (1.0 - c));
    }
}

TEST(Warps, UniformTriangleBarycentrics)
{
    // Each barycentric of a uniform point has mean 1/3 and variance 1/18.
    Pcg32 rng(12, 0);
    double b0 = 0.0, b1 = 0.0, b2 = 0.0;
    for (int i = 0; i < kN; ++i) {
        const glm::vec2 b = sampleUniformTriangle(rng.next2());
        ASSERT_GE(b.x, 0.0f);
        ASSERT_GE(b.y, 0.0f);
        ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
        b0 += b.x;
        b1 += b.y;
        b2 += 1.0 - b.x - b.y;
    }
    for (double m : {b0, b1, b2}) EXPECT_NEAR(m / kN, 1.0 / 3.0, tol(1.0 / 18.0));
}

TEST(Warps, ConcentricDiskIsUniform)
{
    // Uniform on the unit disk: E[r^2] = 1/2; a quarter of the points in each quadrant.
    Pcg32 rng(13, 0);
    double r2 = 0.0;
    int quadrant[4] = {};
    for (int i = 0; i < kN; ++i) {
        const glm::vec2 p = sampleConcentricDisk(rng.next2());
        const double rr = double(p.x) * p.x + double(p.y) * p.y;
        ASSERT_LE(rr, 1.0 + 1e-6);
        r2 += rr;
        ++quadrant[(p.x < 0 ? 1 : 0) + (p.y < 0 ? 2 : 0)];
    }
    EXPECT_NEAR(r2 / kN, 0.5, tol(1.0 / 12.0));
    for (int q : quadrant) EXPECT_NEAR(q, kN / 4, 5 * std::sqrt(kN * 0.25 * 0.75));
}

TEST(Halton, RadicalInverseDigits)
{
    EXPECT_EQ(radicalInverse(0, 0), 0.0);
    EXPECT_EQ(radicalInverse(0, 1), 0.5);
    EXPECT_EQ(radicalInverse(0, 2), 0.25);
    EXPECT_EQ(radicalInverse(0, 3), 0.75);
    EXPECT_EQ(radicalInverse(0, 6), 0.375);
    EXPECT_NEAR(radicalInverse(1, 1), 1.0 / 3.0, 1e-15);
    EXPECT_NEAR(radicalInverse(1, 2), 2.0 / 3.0, 1e-15);
    EXPECT_NEAR(radicalInverse(1, 3), 1.0 / 9.0, 1e-15);
    EXPECT_NEAR(radicalInverse(2, 7), 2.0 / 5.0 + 1.0 / 25.0, 1e-15);          // 7 = 12 in base 5
    EXPECT_NEAR(radicalInverse(kHaltonDimensions - 1, 1), 1.0 / 311.0, 1e-15); // the 64th prime
    EXPECT_THROW(radicalInverse(kHaltonDimensions, 1), std::out_of_range);
}

TEST(Halton, FirstPointsStratifyTheSquare)
{
    // The first 2^a 3^b points of the 2-D Halton sequence put exactly one point in each of the
    // 2^a x 3^b elementary boxes (Halton's sequence is a (0,s)-sequence in each prime base).
    const int nx = 8, ny = 9;
    std::vector<int> box(nx * ny, 0);
    for (std::uint64_t i = 0; i < std::uint64_t(nx * ny); ++i)
        // (1e-9: a point exactly on a box edge, k/9, belongs to box k whatever the last bit of rounding)
        ++box[std::size_t(int(halton(1, i) * ny + 1e-9) * nx + int(halton(0, i) * nx + 1e-9))];
    for (int c : box) EXPECT_EQ(c, 1);
}

TEST(Sobol2, EveryRunOfTwoToTheMIsAZeroTwoNet)
{
    // A (0, 2)-sequence in base 2, under every scramble: the points k 2^m .. (k + 1) 2^m - 1 put exactly one
    // point in each 2^a x 2^(m - a) box, for every a. Scrambling keeps this, and changes the points.
    for (std::uint32_t seed : {0u, 1u, 7u})
        for (int m = 0; m <= 8; ++m)
            for (std::uint32_t k = 0; k < 3; ++k)
                for (int a = 0; a <= m; ++a) {
                    const int n = 1 << m, nx = 1 << a, ny = n / nx;
                    std::vector<int> box(std::size_t(n), 0);
                    for (int i = 0; i < n; ++i) {
                        const glm::vec2 p = sobol2(k * std::uint32_t(n) + std::uint32_t(i), seed);
                        ASSERT_TRUE(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f);
                        ++box[std::size_t(int(p.y * float(ny)) * nx + int(p.x * float(nx)))];
                    }
                    for (int c : box) ASSERT_EQ(c, 1) << "seed " << seed << ", 2^" << m << " points, run " << k;
                }
    EXPECT_NE(sobol2(5, 1).x, sobol2(5, 2).x);
    EXPECT_NE(sobol2(5, 1).y, sobol2(5, 2).y);
    EXPECT_NE(sobol2(5, 1).x, sobol2(5, 1).y); // the two dimensions are scrambled apart
}

TEST(DiscreteDistribution, FrequenciesFollowWeights)
{
    const DiscreteDistribution d({1.0, 0.0, 3.0, 0.0, 4.0});
    EXPECT_DOUBLE_EQ(d.total(), 8.0);
    EXPECT_FLOAT_EQ(d.pmf(0), 0.125f);
    EXPECT_FLOAT_EQ(d.pmf(1), 0.0f);
    EXPECT_FLOAT_EQ(d.pmf(2), 0.375f);
    EXPECT_FLOAT_EQ(d.pmf(4), 0.5f);
    Pcg32 rng(14, 0);
    std::vector<int> counts(5, 0);
    for (int i = 0; i < kN; ++i) {
        float remapped = -1.0f;
        const std::size_t k = d.sample(rng.nextFloat(), &remapped);
        ASSERT_GE(remapped, 0.0f);
        ASSERT_LT(remapped, 1.0f);
        ++counts[k];
    }
    EXPECT_EQ(counts[1], 0);
    EXPECT_EQ(counts[3], 0);
    for (std::size_t k : {0u, 2u, 4u}) {
        const double p = d.pmf(k);
        EXPECT_NEAR(counts[k], kN * p, 5 * std::sqrt(kN * p * (1 - p)));
    }
    // The ends of [0, 1) and the edges between bins.
    EXPECT_EQ(d.sample(0.0f), 0u);
    EXPECT_EQ(d.sample(0.125f), 2u);
    EXPECT_EQ(d.sample(0.5f), 4u);
    EXPECT_EQ(d.sample(0x1.fffffep-1f), 4u);
    EXPECT_TRUE(DiscreteDistribution({0.0, 0.0}).empty());
}

TEST(MixBits, SpreadsNeighbouringKeys)
{
    // Neighbouring keys differ in about half of the output bits.
    int bits = 0;
    for (std::uint64_t k = 0; k < 1000; ++k) bits += __builtin_popcountll(mixBits(k) ^ mixBits(k + 1));
    EXPECT_NEAR(bits / 1000.0, 32.0, 2.0);
}

} // namespace
