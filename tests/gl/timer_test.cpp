// Per-pass GPU timings (gl/resource/timer.h) are intervals that fit inside the frame that produced them,
// from the very first frame of a fresh context on: the benchmark times single frames without warm-up.
// Not a speed test: nothing here depends on how fast the machine is.
#include <chrono>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "gl/renderer.h"
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

} // namespace
} // namespace bounce
