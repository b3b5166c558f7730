// The frame's parallel primitives (gl/frame/gpu_sort.h) against the CPU: GpuScan's
// exclusive prefix sums and total against std::exclusive_scan, RadixSort against std::stable_sort on the
// same bits, with words past the count left as they were. The counts are the hard cases of a scan over
// work groups: no word, one word, one less and one more than a group's block, and a count whose block
// sums take three levels of blocks; the sort runs in both of its forms (a GPU's runs and llvmpipe's).
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "gl/frame/gpu_sort.h"
#include "gl/gl.h"
#include "gl/resource/buffer.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

constexpr std::uint32_t kPoison = 0xdeadbeefu; // words past the count, which neither primitive may touch
constexpr std::uint32_t kTotalSlot = 3;

class GpuSortTest : public GlTest {};

std::vector<std::uint32_t> randomWords(std::size_t count, std::uint32_t below, std::uint32_t seed)
{
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::uint32_t> word(0u, below - 1u);
    std::vector<std::uint32_t> v(count);
    for (std::uint32_t& w : v) w = word(rng);
    return v;
}

TEST_F(GpuSortTest, ScanIsTheExclusivePrefixSumAtEveryCount)
{
    gl::GpuScan scan;
    // No word (a total of 0); 1 word; a block and one word on either side; a count whose 4097 block sums
    // need a third level (16M words: the sums stay below 2^32).
    constexpr std::uint32_t b = gl::GpuScan::kBlock;
    for (std::uint32_t count : {0u, 1u, 7u, b - 1, b, b + 1, 70001u, b * b + 1}) {
        std::vector<std::uint32_t> words = randomWords(count, 256u, count);
        std::vector<std::uint32_t> padded = words;
        padded.resize(count + 5, kPoison);
        gl::Buffer data = gl::Buffer::fromVector("test.scan", padded);
        gl::Buffer counters = gl::Buffer::fromVector("test.counters", std::vector<std::uint32_t>(8, kPoison));
        scan.run(data, count, counters, kTotalSlot);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        const std::vector<std::uint32_t> got = data.download<std::uint32_t>();
        const std::vector<std::uint32_t> total = counters.download<std::uint32_t>();

        std::vector<std::uint32_t> want(count);
        std::exclusive_scan(words.begin(), words.end(), want.begin(), 0u);
        std::size_t wrong = 0, first = count;
        for (std::uint32_t i = 0; i < count; ++i)
            if (got[i] != want[i]) wrong += (first = std::min<std::size_t>(first, i), 1);
        EXPECT_EQ(wrong, 0u) << count << " words; first wrong at " << first;
        for (std::uint32_t i = count; i < count + 5; ++i) EXPECT_EQ(got[i], kPoison) << count << " words, word " << i;
        EXPECT_EQ(total[kTotalSlot], std::accumulate(words.begin(), words.end(), 0u)) << count << " words";
        for (std::uint32_t s = 0; s < 8; ++s) {
            if (s != kTotalSlot) {
                EXPECT_EQ(total[s], kPoison) << "counter " << s;
            }
        }
    }
}

// Keys with many equal values in the sorted bits and values that record the input order: the GPU's
// order must be std::stable_sort's, so equal keys keep their order, and bits above `bits` (rounded up to
// a byte) do not take part.
TEST_F(GpuSortTest, RadixSortIsTheStableSortOnItsBits)
{
    for (const std::uint32_t runs : {gl::RadixSort::kGpuRuns, gl::RadixSort::kSoftwareRuns}) {
        SCOPED_TRACE(runs == gl::RadixSort::kGpuRuns ? "a GPU's runs" : "llvmpipe's runs");
        gl::RadixSort sort(runs);
        struct Case {
            std::uint32_t count;
            int bits;
        };
        for (const Case c : {Case{1u, 30}, Case{33u, 8}, Case{5000u, 12}, Case{100003u, 30}, Case{1u << 20, 16}}) {
            std::vector<std::uint32_t> keys = randomWords(c.count, 0xffffffffu, c.count + 1u);
            // Few distinct sorted digits, so that runs of equal keys are long; the bits above stay random.
            for (std::uint32_t& k : keys) k = (k & ~0xffffu) | ((k % 37u) * 1021u & 0xffffu);
            std::vector<std::uint32_t> values(c.count);
            std::iota(values.begin(), values.end(), 0u);
            auto padded = [&](std::vector<std::uint32_t> v) {
                v.resize(c.count + 3, kPoison);
                return v;
            };
            gl::Buffer k = gl::Buffer::fromVector("test.keys", padded(keys));
            gl::Buffer v = gl::Buffer::fromVector("test.values", padded(values));
            gl::Buffer kTmp = gl::Buffer::fromVector("test.keysTmp", padded({}));
            gl::Buffer vTmp = gl::Buffer::fromVector("test.valuesTmp", padded({}));
            gl::Buffer counters = gl::Buffer::fromVector("test.counters", std::vector<std::uint32_t>(8, 0u));
            sort.sort(k, v, kTmp, vTmp, c.count, c.bits, counters, kTotalSlot);
            glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
            const std::vector<std::uint32_t> gotKeys = k.download<std::uint32_t>();
            const std::vector<std::uint32_t> gotValues = v.download<std::uint32_t>();

            const int sortedBits = std::min(32, (c.bits + 7) / 8 * 8);
            const std::uint32_t mask = sortedBits == 32 ? 0xffffffffu : (1u << sortedBits) - 1u;
            std::vector<std::uint32_t> order = values;
            std::stable_sort(order.begin(), order.end(),
                             [&](std::uint32_t a, std::uint32_t b) { return (keys[a] & mask) < (keys[b] & mask); });
            std::size_t wrong = 0, first = c.count;
            for (std::uint32_t i = 0; i < c.count; ++i)
                if (gotValues[i] != order[i] || gotKeys[i] != keys[order[i]])
                    wrong += (first = std::min<std::size_t>(first, i), 1);
            EXPECT_EQ(wrong, 0u) << c.count << " pairs on " << c.bits << " bits; first wrong at " << first;
            for (std::uint32_t i = c.count; i < c.count + 3; ++i) {
                EXPECT_EQ(gotKeys[i], kPoison) << c.count << " pairs, key " << i;
                EXPECT_EQ(gotValues[i], kPoison) << c.count << " pairs, value " << i;
            }
        }
    }
}

} // namespace
} // namespace bounce
