// Random numbers and the warps that turn them into points and directions. Shared by the ground truth
// (ref/) and every CPU-side sampler of the project (VPL placement, point clouds, benchmarks).
//
// Conventions: u, u1, u2 are uniform in [0, 1); directions of the hemisphere warps are in a local frame
// with +z the normal (turn them into world space with Frame); every warp has a pdf function beside it,
// in solid angle (directions) or in area (points).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::core {

// PCG32 (O'Neill 2014, "PCG: a family of simple fast space-efficient statistically good algorithms"):
// a 64-bit linear congruential state with the XSH-RR output permutation. Each (seed, stream) pair is
// an independent sequence: the stream selects the LCG increment. The reference renderer seeds one
// generator per (pixel, sample index), which is what makes its images independent of the thread count.
class Pcg32 {
public:
    explicit Pcg32(std::uint64_t seed = 0x853c49e6748fea9bull, std::uint64_t stream = 0xda3e39cb94b95bdbull)
    {
        reseed(seed, stream);
    }
    void reseed(std::uint64_t seed, std::uint64_t stream);

    std::uint32_t nextU32()
    {
        const std::uint64_t old = state_;
        state_ = old * kMultiplier + inc_;
        const auto xorShifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
        const auto rot = std::uint32_t(old >> 59u);
        return (xorShifted >> rot) | (xorShifted << ((32u - rot) & 31u));
    }
    // Uniform in [0, 1): the top 24 bits, so the result is exactly representable and never 1.
    float nextFloat() { return float(nextU32() >> 8) * 0x1p-24f; }
    double nextDouble() { return double((std::uint64_t(nextU32()) << 21) ^ nextU32()) * 0x1p-53; }
    glm::vec2 next2()
    {
        const float a = nextFloat();
        return {a, nextFloat()};
    }
    // Uniform in [0, bound) without modulo bias (rejection of the short last interval).
    std::uint32_t nextBounded(std::uint32_t bound);
    // Jumps ahead (or back, for negative delta) in O(log |delta|) (Brown 1994, arbitrary-stride LCG jump).
    void advance(std::int64_t delta);

    friend bool operator==(const Pcg32& a, const Pcg32& b) { return a.state_ == b.state_ && a.inc_ == b.inc_; }

private:
    static constexpr std::uint64_t kMultiplier = 6364136223846793005ull;
    std::uint64_t state_ = 0;
    std::uint64_t inc_ = 1;
};

// A 64-bit finaliser (splitmix64): turns structured keys (pixel index, seed) into well-mixed seeds.
std::uint64_t mixBits(std::uint64_t v);

// Orthonormal basis around a unit normal, branchless and robust at every orientation
// (Duff et al. 2017, "Building an Orthonormal Basis, Revisited", JCGT 6(1), Listing 3).
struct Frame {
    glm::vec3 t, b, n; // right-handed: cross(t, b) == n

    static Frame fromNormal(const glm::vec3& n);
    glm::vec3 toLocal(const glm::vec3& v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
    glm::vec3 toWorld(const glm::vec3& v) const { return v.x * t + v.y * b + v.z * n; }
};

// Concentric map of the square onto the unit disk (Shirley & Chiu 1997): area-preserving, low distortion.
glm::vec2 sampleConcentricDisk(const glm::vec2& u);

// Cosine-weighted hemisphere around +z (Malley's method: a disk point lifted to the hemisphere);
// pdf = cos(theta) / pi.
glm::vec3 sampleCosineHemisphere(const glm::vec2& u);
inline float cosineHemispherePdf(float cosTheta)
{
    return cosTheta > 0.0f ? cosTheta * 0.31830988618379067f : 0.0f;
}

// Uniform on the unit sphere; pdf = 1 / (4 pi).
glm::vec3 sampleUniformSphere(const glm::vec2& u);
inline float uniformSpherePdf()
{
    return 0.07957747154594767f;
}

// Uniform in the cone of directions around +z with cos(theta) >= cosThetaMax; pdf = 1 / (2 pi (1 - cosThetaMax)).
glm::vec3 sampleUniformCone(const glm::vec2& u, float cosThetaMax);
inline float uniformConePdf(float cosThetaMax)
{
    return 1.0f / (2.0f * 3.14159265358979323846f * (1.0f - cosThetaMax));
}

// Uniform on a triangle: barycentrics (b0, b1) of p = b0 p0 + b1 p1 + (1 - b0 - b1) p2, by the
// square-root warp (Osada et al. 2002, Eq. 1); the area pdf is 1 / area.
glm::vec2 sampleUniformTriangle(const glm::vec2& u);

// Radical inverse of `index` in base prime(dimension) (dimension 0 is base 2, 1 is base 3, ...), in [0, 1).
// Dimensions 0..kHaltonDimensions-1 are supported.
inline constexpr int kHaltonDimensions = 64;
double radicalInverse(int dimension, std::uint64_t index);
// The Halton sequence (Halton 1960): point `index`, coordinate `dimension`; unscrambled.
inline double halton(int dimension, std::uint64_t index)
{
    return radicalInverse(dimension, index);
}

// The first two dimensions of Sobol's sequence (Sobol 1967), point `index`, Owen-scrambled by `seed`
// (nested uniform scrambling by Laine and Karras's hash; Burley 2020). A (0, 2)-sequence in base 2: every
// run of 2^m points from a multiple of 2^m puts exactly one point in each of any 2^m equal boxes of
// 2^a x 2^(m-a), so 16 still frames sample a light 4 x 4. Halton's high bases (5 and 7 and up) lie on
// lines for their first points. Each seed is another, independent, scrambling.
glm::vec2 sobol2(std::uint32_t index, std::uint32_t seed);

// A discrete distribution over weights (not necessarily normalised), sampled by inversion of the CDF
// (binary search). Zero weights are never chosen; all-zero weights give an empty distribution.
class DiscreteDistribution {
public:
    DiscreteDistribution() = default;
    explicit DiscreteDistribution(const std::vector<double>& weights);

    bool empty() const { return total_ <= 0.0; }
    std::size_t size() const { return pmf_.size(); }
    double total() const { return total_; }
    float pmf(std::size_t i) const { return pmf_[i]; }
    // The index for u in [0, 1); `remapped` (optional) returns u rescaled to [0, 1) inside the chosen bin.
    std::size_t sample(float u, float* remapped = nullptr) const;

private:
    std::vector<float> pmf_;
    std::vector<double> cdf_; // size() + 1 entries, cdf_[0] = 0, cdf_.back() = 1
    double total_ = 0.0;
};

} // namespace bounce::core
