// The frame's size check (gl/frame/frame_budget.h): limits of the driver's textures, viewports and
// framebuffers and of memory, checked before any render target is allocated; and the bytes per pixel it
// assumes are those the frame really allocates.
#include <string>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "gl/frame/frame.h"
#include "gl/frame/frame_budget.h"
#include "gl/resource/allocations.h"
#include "gl/resource/resource_error.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

gl::DeviceLimits limits(std::size_t availableBytes)
{
    gl::DeviceLimits l;
    l.maxTextureSize = 16384;
    l.maxViewportWidth = l.maxViewportHeight = 16384;
    l.maxFramebufferWidth = l.maxFramebufferHeight = 16384;
    l.availableBytes = availableBytes;
    l.memorySource = "test memory";
    return l;
}

gl::FrameSettings sized(int w, int h)
{
    gl::FrameSettings s;
    s.width = w;
    s.height = h;
    return s;
}

TEST(FrameBudget, SizesOverTheLimitsAreNamed)
{
    const std::size_t eightGiB = std::size_t(8) << 30;
    EXPECT_EQ(gl::frameFitProblem(sized(512, 512), limits(eightGiB)), "");
    EXPECT_EQ(gl::frameFitProblem(sized(4096, 4096), limits(0)), "") << "unknown memory: sizes only";
    const std::string tooWide = gl::frameFitProblem(sized(20000, 16), limits(eightGiB));
    EXPECT_NE(tooWide.find("GL_MAX_TEXTURE_SIZE (16384)"), std::string::npos) << tooWide;
    EXPECT_NE(tooWide.find("--size 20000x16"), std::string::npos) << tooWide;
    gl::DeviceLimits narrowViewport = limits(eightGiB);
    narrowViewport.maxViewportWidth = narrowViewport.maxViewportHeight = 8192;
    EXPECT_NE(gl::frameFitProblem(sized(10000, 16), narrowViewport).find("GL_MAX_VIEWPORT_DIMS"), std::string::npos);
    // 16384^2 pixels x 108 bytes = 27 GiB of targets against 8 GiB.
    const std::string tooBig = gl::frameFitProblem(sized(16384, 16384), limits(eightGiB));
    EXPECT_NE(tooBig.find("--size 16384x16384"), std::string::npos) << tooBig;
    EXPECT_NE(tooBig.find("21.00 GiB"), std::string::npos) << tooBig; // 16384^2 x 84 bytes
    EXPECT_NE(tooBig.find("test memory"), std::string::npos) << tooBig;
}

class FrameBudgetTest : public GlTest {};

// frameTargetBytesPerPixel() is what Frame::allocateTargets() registers (gl/resource/allocations.h) for an
// odd size: if a target's format changes and the estimate does not, this fails.
// The specular and emission targets exist only where the scene has glossy materials and emitters:
// cornell-spot needs neither, cornell-area an emission target, cornell-glossy both.
TEST_F(FrameBudgetTest, BytesPerPixelAreTheFramesOwn)
{
    const struct {
        const char* scene;
        bool specular, emission;
    } cases[] = {{"cornell-spot", false, false}, {"cornell-area", false, true}, {"cornell-glossy", true, true}};
    for (const auto& c : cases) {
        SCOPED_TRACE(c.scene);
        const std::size_t before = gl::Allocations::instance().totalBytes();
        const core::Scene scene = core::makeCornell(c.scene);
        gl::FrameSettings s = sized(37, 23);
        s.shadowMapSize = 64;
        gl::Frame frame(scene, s);
        EXPECT_EQ(frame.hasSpecularTarget(), c.specular);
        EXPECT_EQ(frame.hasEmissionTarget(), c.emission);
        std::size_t targets = 0;
        for (const auto& [label, bytes] : gl::Allocations::instance().byLabel())
            if (label.rfind("gbuffer.", 0) == 0 || label == "direct" || label == "indirect" || label == "composite")
                targets += bytes;
        EXPECT_EQ(targets, std::size_t(37 * 23) * gl::frameTargetBytesPerPixel(c.specular, c.emission));
        EXPECT_GT(gl::Allocations::instance().totalBytes(), before);
    }
}

// The current driver's limits are read and a frame within them is allowed.
TEST_F(FrameBudgetTest, DriverLimitsAreRead)
{
    const gl::DeviceLimits l = gl::deviceLimits();
    EXPECT_GE(l.maxTextureSize, 1024);
    EXPECT_GE(l.maxViewportWidth, 1024);
    EXPECT_GE(l.maxFramebufferWidth, 1024);
    std::printf("[ limits   ] texture %d, viewport %dx%d, framebuffer %dx%d, memory %.2f GiB (%s)\n", l.maxTextureSize,
                l.maxViewportWidth, l.maxViewportHeight, l.maxFramebufferWidth, l.maxFramebufferHeight,
                double(l.availableBytes) / double(1ull << 30), l.memorySource.c_str());
    EXPECT_NO_THROW(gl::checkFrameFits(sized(64, 64)));
}

} // namespace
} // namespace bounce
