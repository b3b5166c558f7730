// The GPU's median-split order (gl/frame/points/median_split.h) against the CPU's (core::medianSplitOrder,
// every level): the same permutation, point for point. The clouds are the hard cases of a kd split: counts
// that are no power of two (segments whose halves differ by one, a single point, none), more flags than
// one block of the scan, coordinates that tie (a grid, every point on the same spot), -0 beside +0, NaN
// and infinities (ordered as the origin), and scenes a million times smaller and larger than a metre.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/point_order.h"
#include "gl/frame/points/median_split.h"
#include "gl/resource/buffer.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class MedianSplitTest : public GlTest {};

std::vector<glm::vec3> onABox(std::size_t count, float scale, std::uint32_t seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<glm::vec3> p(count);
    for (glm::vec3& q : p) {
        q = glm::vec3(u(rng), u(rng), u(rng)) * glm::vec3(2.0f, 1.0f, 0.5f);
        const int face = int(u(rng) * 3.0f) % 3;
        q[face] = u(rng) < 0.5f ? 0.0f : (face == 0 ? 2.0f : face == 1 ? 1.0f : 0.5f);
        q *= scale;
    }
    return p;
}

// The GPU's order of `positions`, uploaded 4 floats apart (the surfels are 8 apart: PointprojTest).
std::vector<std::uint32_t> gpuOrder(gl::MedianSplit& split, const std::vector<glm::vec3>& positions)
{
    std::vector<float> words;
    for (const glm::vec3& p : positions) words.insert(words.end(), {p.x, p.y, p.z, 1.0f});
    words.resize(std::max<std::size_t>(words.size(), 4));
    const gl::Buffer buffer = gl::Buffer::fromVector("test.positions", words);
    const auto n = std::uint32_t(positions.size());
    std::vector<std::uint32_t> order(n);
    if (n > 0) split.order(buffer, 4, n).download(0, n * 4u, order.data());
    return order;
}

TEST_F(MedianSplitTest, GpuOrderIsTheCpuOrder)
{
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<std::pair<std::string, std::vector<glm::vec3>>> clouds = {
        {"no point", {}},
        {"one point", {{1, 2, 3}}},
        {"three points", {{0, 0, 0}, {2, 0, 0}, {1, 0, 0}}},
        {"1000 on a box", onABox(1000, 1.0f, 1)},
        {"5000 on a box (15,000 flags: four blocks of the scan)", onABox(5000, 1.0f, 2)},
        {"4096 a millionth of a metre across", onABox(4096, 1e-6f, 3)},
        {"4096 a million metres across", onABox(4096, 1e6f, 4)},
    };
    std::vector<glm::vec3> grid, same(777, glm::vec3(0.25f, -1.0f, 3.0f)), odd = onABox(1500, 1.0f, 5);
    for (int i = 0; i < 2000; ++i) grid.push_back(glm::vec3(float(i % 3), float((i / 3) % 5), float(i % 7)) * 0.5f);
    for (std::size_t i = 0; i < odd.size(); i += 7) odd[i] = glm::vec3(i % 2 ? -0.0f : 0.0f, 0.0f, 0.0f);
    for (std::size_t i = 3; i < odd.size(); i += 11) odd[i].y = (i % 3 == 0) ? nan : (i % 3 == 1 ? inf : -inf);
    clouds.push_back({"2000 on a grid of ties", grid});
    clouds.push_back({"777 on one spot", same});
    clouds.push_back({"1500 with -0, +0, NaN and infinities", odd});

    gl::MedianSplit split;
    for (const auto& [name, positions] : clouds) {
        SCOPED_TRACE(name);
        const std::vector<std::uint32_t> cpu = core::medianSplitOrder(positions, 64);
        const std::vector<std::uint32_t> gpu = gpuOrder(split, positions);
        ASSERT_EQ(gpu.size(), cpu.size());
        std::size_t differ = 0, first = cpu.size();
        for (std::size_t i = 0; i < cpu.size(); ++i)
            if (gpu[i] != cpu[i]) {
                ++differ;
                first = std::min(first, i);
            }
        EXPECT_EQ(differ, 0u) << "positions where the orders differ, the first at " << first;
    }
    EXPECT_EQ(gl::MedianSplit::levels(0), 0);
    EXPECT_EQ(gl::MedianSplit::levels(1), 0);
    EXPECT_EQ(gl::MedianSplit::levels(3), 2);
    EXPECT_EQ(gl::MedianSplit::levels(65536), 16);
}

} // namespace
} // namespace bounce
