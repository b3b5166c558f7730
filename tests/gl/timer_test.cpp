// Per-pass GPU timings (gl/resource/timer.h) are intervals that fit inside the frame that produced them,
// from the very first frame of a fresh context on: the benchmark times single frames without warm-up.
// Not a speed test: nothing here depends on how fast the machine is.
#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "gl/context/context.h"
#include "gl/debug.h"
#include "gl/gl.h"
#include "gl/renderer.h"
#include "gl/resource/buffer.h"
#include "gl/resource/dispatch.h"
#include "gl/resource/program.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class TimerTest : public GlTest {};

// The first frame of a new context: every pass's GPU time is non-negative and no longer than the
// wall-clock time of the whole frame (endFrame waits for the results, so the GPU work lies inside it).
// llvmpipe used to answer the context's first query with a timestamp: 35 minutes for a 10 ms pass.
TEST_F(TimerTest, FirstFrameOfAContextGivesIntervalsInsideTheFrame)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("shadow.size", 256);
    gl::Renderer r(scene, "direct", frameValues, gl::ParamValues(), 32, 32);
    const auto start = std::chrono::steady_clock::now();
    r.renderFrame(true);
    const double wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const std::vector<gl::PassStat> stats = r.timers().stats();
    ASSERT_FALSE(stats.empty());
    for (const gl::PassStat& p : stats) {
        EXPECT_EQ(p.frames, 1) << p.pass;
        EXPECT_GE(p.medianMs, 0.0) << p.pass;
        EXPECT_LE(p.medianMs, wallMs) << p.pass << ": a pass longer than its frame (" << wallMs << " ms)";
    }
}

std::vector<std::string>& pushedGroups()
{
    static std::vector<std::string> names;
    return names;
}

void GLAD_API_PTR recordPushGroup(GLenum source, GLenum type, GLuint, GLenum, GLsizei length, const GLchar* text,
                                  const void*)
{
    if (type == GL_DEBUG_TYPE_PUSH_GROUP && source == GL_DEBUG_SOURCE_APPLICATION)
        pushedGroups().emplace_back(text, length >= 0 ? std::size_t(length) : std::string(text).size());
}

// Every timed pass is a KHR_debug group named after it (what a capture shows): with debug output on, the
// push-group messages of one frame carry exactly the pass names the timers report, in order.
TEST_F(TimerTest, EveryTimedPassIsADebugGroupNamedAfterIt)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("shadow.size", 64);
    gl::Renderer r(scene, "direct", frameValues, gl::ParamValues(), 32, 32);
    pushedGroups().clear();
    glDebugMessageCallback(recordPushGroup, nullptr);
    // Group messages have notification severity, which installDebugCallback() mutes.
    glDebugMessageControl(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_PUSH_GROUP, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    r.renderFrame(true);
    gl::installDebugCallback();
    std::vector<std::string> passes;
    for (const gl::PassStat& p : r.timers().stats()) passes.push_back(p.pass);
    ASSERT_FALSE(passes.empty());
    std::vector<std::string> groups = pushedGroups();
    groups.erase(std::unique(groups.begin(), groups.end()), groups.end()); // a pass may run per light
    EXPECT_EQ(groups, passes);
}

// A pass's work is its counted invocations times its declared cost: a compute dispatch of exactly N
// invocations (no partial groups) gives N and N x cost; a full-screen fragment pass over W x H pixels
// gives at least W x H fragment invocations (a rasteriser may count helper or masked lanes too, never fewer).
TEST_F(TimerTest, PassWorkIsCountedInvocationsTimesDeclaredCost)
{
    if (!gl::hasGlExtension("GL_ARB_pipeline_statistics_query"))
        GTEST_SKIP() << "the driver counts no invocations (GL_ARB_pipeline_statistics_query)";
    gl::Program compute = gl::Program::compute("test.cover", "test/dispatch_cover.comp",
                                               {{"LOCAL_X", "8"}, {"LOCAL_Y", "8"}, {"LOCAL_Z", "1"}});
    gl::Buffer marks("test.marks", (1 + 4096) * sizeof(unsigned));
    marks.clearToZero();
    gl::PassTimers timers;
    gl::PassCost cost;
    cost.flops = 3;
    cost.bytesWritten = 4;
    cost.bytesFixed = 100;
    {
        auto t = timers.scope("count", cost);
        marks.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
        compute.set("size", glm::ivec3(64, 64, 1));
        compute.use();
        glDispatchCompute(8, 8, 1); // local size 8x8x1: 4096 invocations
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
        gl::PassCost later;
        later.flopsFixed = 1000;
        t.addWork(later);
    }
    timers.endFrame();
    const std::vector<gl::PassStat> stats = timers.stats();
    ASSERT_EQ(stats.size(), 1u);
    const gl::PassWork& w = stats[0].work;
    EXPECT_EQ(w.computeInvocations, 4096.0);
    EXPECT_EQ(w.fragmentInvocations, 0.0);
    EXPECT_TRUE(w.costDeclared);
    EXPECT_EQ(w.flops, 4096.0 * 3 + 1000);
    EXPECT_EQ(w.bytes, 4096.0 * 4 + 100);
}

// A pass's declared invocations (Scope::expectComputes/expectFragments) add up over the calls and over the
// scopes of the pass in a frame; a compute dispatch with partial groups declares, and the driver counts, the
// idle invocations of those groups too (computeInvocations); a viewport declares its pixels and, as the most
// a driver may count, the 4x4 blocks of the framebuffer it touches and those of its diagonal once more. A
// pass with one scope that declares nothing declares nothing.
TEST_F(TimerTest, DeclaredInvocationsAddUpOverScopes)
{
    if (!gl::hasGlExtension("GL_ARB_pipeline_statistics_query"))
        GTEST_SKIP() << "the driver counts no invocations (GL_ARB_pipeline_statistics_query)";
    gl::Program compute = gl::Program::compute("test.cover", "test/dispatch_cover.comp",
                                               {{"LOCAL_X", "8"}, {"LOCAL_Y", "8"}, {"LOCAL_Z", "1"}});
    gl::Buffer marks("test.marks", (1 + 10 * 10) * sizeof(unsigned));
    marks.clearToZero();
    marks.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    compute.set("size", glm::ivec3(10, 10, 1));
    EXPECT_EQ(gl::computeInvocations({10, 10, 1}, {8, 8, 1}), 256.0); // 2 x 2 groups of 64
    gl::PassTimers timers;
    for (int i = 0; i < 2; ++i) {
        auto t = timers.scope("cover");
        t.expectComputes(gl::computeInvocations({10, 10, 1}, {8, 8, 1}));
        gl::dispatchCompute(compute, {10, 10, 1}, {8, 8, 1});
        t.expectFragments(5, 3, 2, 1); // x 2..6, y 1..3: blocks 0..1 by 0
    }
    {
        auto t = timers.scope("silent");
    }
    {
        auto t = timers.scope("half");
        t.expectComputes(0.0);
    }
    {
        auto t = timers.scope("half");
    }
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    timers.endFrame();
    const std::vector<gl::PassStat> stats = timers.stats();
    ASSERT_EQ(stats.size(), 3u);
    const gl::PassWork& cover = stats[0].work;
    EXPECT_EQ(cover.computeInvocations, 512.0);
    ASSERT_TRUE(cover.expectedComputeInvocations.has_value());
    EXPECT_EQ(*cover.expectedComputeInvocations, 512.0);
    ASSERT_TRUE(cover.expectedFragmentInvocations.has_value());
    EXPECT_EQ(*cover.expectedFragmentInvocations, 2 * 15.0);
    EXPECT_EQ(cover.expectedFragmentInvocationsAtMost, 2 * (2 * 1 + 2 + 1 - 1) * 16.0); // 2 x 1 blocks, a diagonal of 2
    EXPECT_FALSE(stats[1].work.expectedComputeInvocations.has_value());
    EXPECT_FALSE(stats[1].work.expectedFragmentInvocations.has_value());
    EXPECT_FALSE(stats[2].work.expectedComputeInvocations.has_value()) << "one of the pass's scopes declared none";
}

TEST_F(TimerTest, FragmentPassCountsAtLeastItsPixels)
{
    if (!gl::hasGlExtension("GL_ARB_pipeline_statistics_query"))
        GTEST_SKIP() << "the driver counts no invocations (GL_ARB_pipeline_statistics_query)";
    const core::Scene scene = core::makeCornell("cornell-spot");
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("shadow.size", 64);
    gl::Renderer r(scene, "direct", frameValues, gl::ParamValues(), 37, 23); // not a multiple of 2, 4 or 8
    r.renderFrame(true);
    bool sawDirect = false;
    for (const gl::PassStat& p : r.timers().stats()) {
        if (p.pass != "direct") continue; // the full-screen direct-light pass
        sawDirect = true;
        EXPECT_GE(p.work.fragmentInvocations, 37.0 * 23.0);
        EXPECT_LE(p.work.fragmentInvocations, 2.0 * 40 * 24) << "a full-screen pass counts about its pixels";
        EXPECT_TRUE(p.work.costDeclared);
        EXPECT_GT(p.work.bytes, 0.0);
    }
    EXPECT_TRUE(sawDirect);
}

} // namespace
} // namespace bounce
