// Poisoned new storage (gl/resource/allocations.h): with poisoning on, a buffer made without data holds
// 0xff bytes and a texture NaN (float formats), 1 (normalised), all ones (integer) or 0.5 (depth) in
// every level until a pass writes it; data given at creation is kept. Every GL test runs with poisoning
// on (GlTest, and the app tests' runs of bounce), so that a pass reading storage no pass wrote fails on
// llvmpipe as it would on a GPU driver that hands out old memory.
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "gl/gl.h"
#include "gl/resource/allocations.h"
#include "gl/resource/buffer.h"
#include "gl/resource/texture.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class PoisonTest : public GlTest {
protected:
    void SetUp() override
    {
        GlTest::SetUp();
        was_ = gl::poisonNewStorage();
        gl::setPoisonNewStorage(true);
    }
    void TearDown() override
    {
        gl::setPoisonNewStorage(was_);
        GlTest::TearDown();
    }
    bool was_ = false;
};

TEST_F(PoisonTest, BufferWithoutDataHoldsOnesAndOneWithDataKeepsIt)
{
    const gl::Buffer empty("test.poisoned", 10); // not a multiple of four
    std::vector<std::uint8_t> bytes(10, 0);
    empty.download(0, bytes.size(), bytes.data());
    for (std::size_t i = 0; i < bytes.size(); ++i) EXPECT_EQ(bytes[i], 0xff) << "byte " << i;

    const std::vector<std::uint32_t> given = {1, 2, 3};
    const gl::Buffer full = gl::Buffer::fromVector("test.given", given);
    EXPECT_EQ(full.download<std::uint32_t>(), given);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(PoisonTest, EveryLevelOfATextureHoldsPoisonForItsFormat)
{
    const gl::Texture f = gl::Texture::create2D("test.float", GL_RGBA32F, 5, 3, 3); // odd sizes, three levels
    for (int level = 0; level < 3; ++level)
        for (float v : f.readFloats(level, 4)) EXPECT_TRUE(std::isnan(v)) << "level " << level << ": " << v;

    const gl::Texture half = gl::Texture::create2D("test.half", GL_RG16F, 4, 4);
    for (float v : half.readFloats(0, 2)) EXPECT_TRUE(std::isnan(v)) << v;

    const gl::Texture unorm = gl::Texture::create2D("test.unorm", GL_RGBA8, 4, 4);
    for (float v : unorm.readFloats(0, 4)) EXPECT_EQ(v, 1.0f);

    const gl::Texture integer = gl::Texture::create2D("test.uint", GL_R32UI, 3, 2);
    std::vector<std::uint32_t> words(6, 0);
    glGetTextureImage(integer.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(words.size() * 4), words.data());
    for (std::uint32_t w : words) EXPECT_EQ(w, 0xffffffffu);

    const gl::Texture depth = gl::Texture::create2DArray("test.depth", GL_DEPTH_COMPONENT32F, 2, 2, 3);
    std::vector<float> d(12, 0.0f);
    glGetTextureImage(depth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(d.size() * 4), d.data());
    for (float v : d) EXPECT_EQ(v, 0.5f);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

} // namespace
} // namespace bounce
