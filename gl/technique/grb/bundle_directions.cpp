#include "gl/technique/grb/bundle_directions.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/sampling.h"
#include "gl/frame/frame_sampler.h"

namespace bounce::gl {

std::uint64_t bundleSequenceIndex(std::uint64_t index)
{
    // Fisher-Yates over the block, driven by a hash of the block's number: the same permutation every
    // call, a different one per block.
    const std::uint64_t block = index / kBundleShuffleBlock;
    std::array<std::uint32_t, kBundleShuffleBlock> order;
    for (std::uint32_t j = 0; j < kBundleShuffleBlock; ++j) order[j] = j;
    std::uint64_t state = core::mixBits(block + 0x9e3779b97f4a7c15ull);
    for (std::uint32_t j = kBundleShuffleBlock - 1; j > 0; --j) {
        state = core::mixBits(state + j);
        std::swap(order[j], order[state % (j + 1)]);
    }
    return block * kBundleShuffleBlock + order[index % kBundleShuffleBlock];
}

glm::vec3 bundleDirection(std::uint64_t index)
{
    return core::sampleUniformSphere(
        FrameSampler::sample2(SampleStream::BundleDirection, bundleSequenceIndex(index) + 1));
}

glm::vec2 bundleJitter(std::uint64_t index)
{
    return FrameSampler::sample2(SampleStream::BundleJitter, bundleSequenceIndex(index) + 1);
}

BundleView bundleView(const core::Bounds& bounds, glm::vec3 dir, glm::vec2 jitter, int size)
{
    BundleView v;
    v.dir = glm::normalize(dir);
    const core::Frame f = core::Frame::fromNormal(v.dir);
    v.right = f.t;
    v.up = f.b;
    v.centre = bounds.centre();
    v.radius = std::max(0.5f * glm::length(bounds.extent()) * 1.01f, 1e-6f);
    v.jitter = jitter;
    v.size = size;
    // clip.x = ((dot(p - c, right) + r) / 2r * size + jitter.x) / size * 2 - 1, likewise y; clip.z =
    // dot(p - c, dir) / r. Columns of the matrix (GLM is column-major).
    const float s = 1.0f / v.radius;
    const glm::vec2 shift = 2.0f * jitter / float(size);
    glm::mat4 m(0.0f);
    for (int a = 0; a < 3; ++a) {
        m[a][0] = v.right[a] * s;
        m[a][1] = v.up[a] * s;
        m[a][2] = v.dir[a] * s;
    }
    m[3][0] = -glm::dot(v.centre, v.right) * s + shift.x;
    m[3][1] = -glm::dot(v.centre, v.up) * s + shift.y;
    m[3][2] = -glm::dot(v.centre, v.dir) * s;
    m[3][3] = 1.0f;
    v.viewProj = m;
    return v;
}

} // namespace bounce::gl
