// The frame's sampler (gl/frame/frame_sampler.h): no two consumers draw from the same dimensions of one
// sequence, the frame's own streams are the points they were before the sampler owned them (so that every
// still image is unchanged), and the still index and jitter follow still and moving frames. No GL.
#include <cmath>
#include <set>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "core/sampling.h"
#include "gl/frame/frame_sampler.h"

namespace bounce {
namespace {

using gl::FrameSampler;
using gl::SampleSequence;
using gl::SampleStream;

// Whether the table declares that a and b share their numbers (either way round).
bool declared(const gl::SampleStreamInfo& a, const gl::SampleStreamInfo& b)
{
    return (a.shares && std::string(a.shares) == b.name) || (b.shares && std::string(b.shares) == a.name);
}

// Two streams of Halton's sequence with a dimension in common, or of Sobol's with one scrambling, draw the
// same numbers: only the pairs the table declares may (grb's, at their own indices, with the reason there).
TEST(FrameSampler, NoTwoStreamsShareADimension)
{
    const auto& all = FrameSampler::streams();
    std::set<std::string> names;
    for (const gl::SampleStreamInfo& s : all) {
        EXPECT_TRUE(names.insert(s.name).second) << "two streams named " << s.name;
        EXPECT_EQ(&FrameSampler::info(s.stream), &s) << s.name << ": the table is out of SampleStream's order";
        if (s.sequence == SampleSequence::Halton) {
            EXPECT_TRUE(s.firstDimension >= 0 && s.firstDimension + 1 < core::kHaltonDimensions) << s.name;
        }
    }
    for (std::size_t i = 0; i < all.size(); ++i)
        for (std::size_t j = i + 1; j < all.size(); ++j) {
            const gl::SampleStreamInfo &a = all[i], &b = all[j];
            if (a.sequence != b.sequence) continue;
            const bool shared = a.sequence == SampleSequence::Halton ? std::abs(a.firstDimension - b.firstDimension) < 2
                                                                     : a.seed == b.seed;
            EXPECT_EQ(shared, declared(a, b)) << a.name << " and " << b.name
                                              << (shared ? " share their numbers without saying so"
                                                         : " are declared to share numbers they do not share");
        }
}

// Streams not declared to share drawn at the same index are not the same numbers.
TEST(FrameSampler, StreamsDrawDifferentPointsAtTheSameIndex)
{
    const auto& all = FrameSampler::streams();
    for (std::size_t a = 0; a < all.size(); ++a)
        for (std::size_t b = a + 1; b < all.size(); ++b) {
            if (declared(all[a], all[b])) continue;
            int same = 0;
            for (std::uint64_t i = 1; i <= 64; ++i)
                same += FrameSampler::sample2(all[a].stream, i) == FrameSampler::sample2(all[b].stream, i);
            EXPECT_EQ(same, 0) << all[a].name << " and " << all[b].name;
        }
}

// Every stream is the points its consumer drew before the sampler owned them (so that every image is
// unchanged): the pixel jitter Halton (0, 1), the shadow maps' shift (4, 5), the glossy lobes' rotation
// (6, 7), the area-light point Sobol scrambled by seed 1, grb's directions (0, 1), offsets (2, 3) and atlas
// rotations (6, 7).
TEST(FrameSampler, TheFramesStreamsAreTheSameSequences)
{
    for (std::uint64_t i = 0; i < 300; ++i) {
        const auto halton2 = [&](int d) { return glm::vec2(float(core::halton(d, i)), float(core::halton(d + 1, i))); };
        EXPECT_EQ(FrameSampler::sample2(SampleStream::PixelJitter, i), halton2(0));
        EXPECT_EQ(FrameSampler::sample2(SampleStream::ShadowShift, i), halton2(4));
        EXPECT_EQ(FrameSampler::sample2(SampleStream::AreaGlossyRotation, i), halton2(6));
        EXPECT_EQ(FrameSampler::sample2(SampleStream::AreaLightPoint, i), core::sobol2(std::uint32_t(i), 1u));
        EXPECT_EQ(FrameSampler::sample2(SampleStream::BundleDirection, i), halton2(0));
        EXPECT_EQ(FrameSampler::sample2(SampleStream::BundleJitter, i), halton2(2));
        EXPECT_EQ(FrameSampler::sample2(SampleStream::AtlasAreaRotation, i), halton2(6));
    }
}

// Every frame advances the frame index; still frames the still index and the jitter; a moving frame puts
// both back to 0 (the pixel's centre). Every value drawn lies in [0, 1), at the largest index too (Halton's
// base 2 at 2^32 - 1 is 1 - 2^-32, which a float rounds to 1).
TEST(FrameSampler, StillAndMovingFrames)
{
    FrameSampler s;
    s.advance(false);
    EXPECT_EQ(s.frameIndex(), 0u);
    EXPECT_EQ(s.stillIndex(), 0);
    EXPECT_EQ(s.jitter(), glm::vec2(0.0f));
    for (int k = 1; k <= 5; ++k) {
        s.advance(true);
        EXPECT_EQ(s.stillIndex(), k);
        EXPECT_EQ(s.jitter(), FrameSampler::sample2(SampleStream::PixelJitter, std::uint64_t(k)) - 0.5f);
        EXPECT_TRUE(std::abs(s.jitter().x) <= 0.5f && std::abs(s.jitter().y) <= 0.5f);
    }
    s.advance(false);
    EXPECT_EQ(s.frameIndex(), 6u);
    EXPECT_EQ(s.stillIndex(), 0);
    EXPECT_EQ(s.jitter(), glm::vec2(0.0f));
    for (const gl::SampleStreamInfo& info : FrameSampler::streams())
        for (std::uint64_t i : {0ull, 1ull, 2ull, 1000ull, 4294967295ull}) {
            const glm::vec2 v = FrameSampler::sample2(info.stream, i);
            EXPECT_TRUE(v.x >= 0.0f && v.x < 1.0f && v.y >= 0.0f && v.y < 1.0f) << info.name << " at " << i;
        }
}

} // namespace
} // namespace bounce
