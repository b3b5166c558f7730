#include "core/sampling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bounce::core {

void Pcg32::reseed(std::uint64_t seed, std::uint64_t stream)
{
    // The initialisation of O'Neill's reference: the increment must be odd; two steps mix the seed in.
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    nextU32();
    state_ += seed;
    nextU32();
}

std::uint32_t Pcg32::nextBounded(std::uint32_t bound)
{
    if (bound <= 1) return 0;
    // 2^32 mod bound values at the bottom would be over-represented by a plain modulo.
    const std::uint32_t threshold = (0u - bound) % bound;
    for (;;) {
        const std::uint32_t r = nextU32();
        if (r >= threshold) return r % bound;
    }
}

void Pcg32::advance(std::int64_t delta)
{
    // state_n = A^n state + (A^(n-1) + ... + 1) c, built by squaring (Brown 1994, "Random number
    // generation with arbitrary strides"); unsigned wrap-around makes negative deltas work.
    auto n = std::uint64_t(delta);
    std::uint64_t curMult = kMultiplier, curPlus = inc_, accMult = 1, accPlus = 0;
    while (n > 0) {
        if (n & 1u) {
            accMult *= curMult;
            accPlus = accPlus * curMult + curPlus;
        }
        curPlus = (curMult + 1) * curPlus;
        curMult *= curMult;
        n >>= 1u;
    }
    state_ = accMult * state_ + accPlus;
}

std::uint64_t mixBits(std::uint64_t v)
{
    v += 0x9e3779b97f4a7c15ull;
    v = (v ^ (v >> 30u)) * 0xbf58476d1ce4e5b9ull;
    v = (v ^ (v >> 27u)) * 0x94d049bb133111ebull;
    return v ^ (v >> 31u);
}

Frame Frame::fromNormal(const glm::vec3& n)
{
    // Duff et al. 2017, Listing 3: copysign picks the branch without a branch, and the basis stays
    // orthonormal to float precision even for n close to -z (where Frisvad's version breaks down).
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    Frame f;
    f.t = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
    f.b = {b, sign + n.y * n.y * a, -n.y};
    f.n = n;
    return f;
}

glm::vec2 sampleConcentricDisk(const glm::vec2& u)
{
    const glm::vec2 o = 2.0f * u - 1.0f;
    if (o.x == 0.0f && o.y == 0.0f) return {0.0f, 0.0f};
    constexpr float kPiOver4 = 0.78539816339744831f;
    float r, theta;
    if (std::abs(o.x) > std::abs(o.y)) {
        r = o.x;
        theta = kPiOver4 * (o.y / o.x);
    } else {
        r = o.y;
        theta = 2.0f * kPiOver4 - kPiOver4 * (o.x / o.y);
    }
    return {r * std::cos(theta), r * std::sin(theta)};
}

glm::vec3 sampleCosineHemisphere(const glm::vec2& u)
{
    const glm::vec2 d = sampleConcentricDisk(u);
    const float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
    return {d.x, d.y, z};
}

glm::vec3 sampleUniformSphere(const glm::vec2& u)
{
    const float z = 1.0f - 2.0f * u.x;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * 3.14159265358979323846f * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

glm::vec3 sampleUniformCone(const glm::vec2& u, float cosThetaMax)
{
    // cos(theta) is uniform in [cosThetaMax, 1] for a uniform solid-angle density.
    const float z = 1.0f - u.x * (1.0f - cosThetaMax);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * 3.14159265358979323846f * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

glm::vec2 sampleUniformTriangle(const glm::vec2& u)
{
    const float s = std::sqrt(u.x);
    return {1.0f - s, u.y * s};
}

namespace {

constexpr std::array<int, kHaltonDimensions> makePrimes()
{
    std::array<int, kHaltonDimensions> primes{};
    int count = 0;
    for (int candidate = 2; count < kHaltonDimensions; ++candidate) {
        bool prime = true;
        for (int d = 2; d * d <= candidate; ++d)
            if (candidate % d == 0) prime = false;
        if (prime) primes[std::size_t(count++)] = candidate;
    }
    return primes;
}

constexpr std::array<int, kHaltonDimensions> kPrimes = makePrimes();

} // namespace

double radicalInverse(int dimension, std::uint64_t index)
{
    if (dimension < 0 || dimension >= kHaltonDimensions)
        throw std::out_of_range("radicalInverse: dimension " + std::to_string(dimension) + " outside 0.." +
                                std::to_string(kHaltonDimensions - 1));
    // Mirror the digits of index in base b about the radix point: sum d_i b^-(i+1).
    // Integer numerator and denominator (base^digits <= base x index < 2^73 fits 128 bits), one division
    // at the end: k / b^n comes out correctly rounded for small n instead of accumulating 1/b errors.
    const auto base = static_cast<unsigned __int128>(kPrimes[std::size_t(dimension)]);
    unsigned __int128 reversed = 0, denominator = 1, rest = index;
    while (rest > 0) {
        const unsigned __int128 next = rest / base;
        reversed = reversed * base + (rest - next * base);
        denominator *= base;
        rest = next;
    }
    return std::min(double(reversed) / double(denominator), 0x1.fffffffffffffp-1);
}

namespace {

std::uint32_t reverseBits(std::uint32_t x)
{
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
    x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
    return (x >> 16) | (x << 16);
}

// Owen's nested uniform scramble of a 32-bit fraction: each bit flipped by a hash of the bits above it.
// Laine and Karras's hash does that for the bits below, so it runs on the reversed fraction.
std::uint32_t owenScramble(std::uint32_t x, std::uint32_t seed)
{
    x = reverseBits(x);
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return reverseBits(x);
}

std::uint32_t hashU32(std::uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

} // namespace

glm::vec2 sobol2(std::uint32_t index, std::uint32_t seed)
{
    // Dimension 0 is the van der Corput sequence; dimension 1's generator matrix is Pascal's triangle mod 2.
    const std::uint32_t x = reverseBits(index);
    std::uint32_t y = 0;
    for (std::uint32_t v = 1u << 31; index != 0; index >>= 1, v ^= v >> 1)
        if (index & 1u) y ^= v;
    // 24 bits: a float in [0, 1) keeps them exactly.
    const auto unit = [](std::uint32_t b) { return float(b >> 8) * 0x1p-24f; };
    return {unit(owenScramble(x, hashU32(seed))), unit(owenScramble(y, hashU32(seed ^ 0x9e3779b9u)))};
}

DiscreteDistribution::DiscreteDistribution(const std::vector<double>& weights)
{
    pmf_.resize(weights.size(), 0.0f);
    cdf_.resize(weights.size() + 1, 0.0);
    for (std::size_t i = 0; i < weights.size(); ++i) {
        const double w = std::isfinite(weights[i]) && weights[i] > 0.0 ? weights[i] : 0.0;
        cdf_[i + 1] = cdf_[i] + w;
    }
    total_ = cdf_.back();
    if (total_ <= 0.0) return;
    for (std::size_t i = 0; i < weights.size(); ++i) {
        cdf_[i + 1] /= total_;
        pmf_[i] = float(cdf_[i + 1] - cdf_[i]);
    }
    cdf_.back() = 1.0;
}

std::size_t DiscreteDistribution::sample(float u, float* remapped) const
{
    // The last bin whose CDF start is <= u; zero-width bins are skipped because upper_bound lands
    // past runs of equal CDF values.
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), double(u));
    std::size_t i = std::size_t(std::max<std::ptrdiff_t>(0, (it - cdf_.begin()) - 1));
    i = std::min(i, pmf_.size() - 1);
    while (pmf_[i] <= 0.0f && i > 0) --i; // only reached through rounding at the very top
    if (remapped) {
        const double width = cdf_[i + 1] - cdf_[i];
        *remapped = width > 0.0 ? std::min(float((double(u) - cdf_[i]) / width), 0x1.fffffep-1f) : 0.0f;
    }
    return i;
}

} // namespace bounce::core
