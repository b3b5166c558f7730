// Issue 57, a cost model that can fail: the work a pass reports is the driver's count of its invocations
// times its declared cost per invocation (gl/resource/timer.h), so a pass that runs more invocations than it
// means to (a dispatch of twice the groups, a viewport of the wrong level, another pass's work timed in its
// scope) reports that much more work and nobody would see it. Here every pass of every technique that
// declares the invocations it runs (PassTimers::Scope::expectFragments/expectComputes) is held to the
// driver's count (GL_ARB_pipeline_statistics_query), frame by frame, at a size that is no multiple of 4 or 8:
//   - compute: exactly the declared count. It is the dispatches' groups times their local size, the idle
//     invocations of the partial groups included (computeInvocations, dispatch.h), which is what a driver
//     launches and counts; no tolerance is needed, and a partial group is not an error.
//   - fragments: at least the declared viewports' pixels, at most the 4x4 blocks of the framebuffer they
//     touch plus one block per block row and column (a diagonal's). llvmpipe counts the blocks its fragment
//     shader ran on, 16 invocations each (lp_query.c: ps_invocations x LP_RASTER_BLOCK_SIZE^2), and those on
//     the diagonal of a full-screen triangle's viewport twice (timer.cpp: 1472 for 37x29, 92 blocks of 80);
//     a GPU shades whole 2x2 quads, inside that bound. The bound for 37x29 is 97 blocks; a doubled viewport
//     or a second draw counts 160 or more.
// Passes that rasterise geometry (G-buffer, shadow maps, RSMs, splats, atlases, the k-buffer) cannot say
// their fragments before the rasteriser ran and declare none; the test prints which passes declared nothing.
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "gl/context/context.h"
#include "gl/renderer.h"
#include "gl/technique/technique.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class InvocationsTest : public GlTest {};

constexpr int kWidth = 37, kHeight = 29; // no multiple of 2, 4 or 8: every dispatch has partial groups

// The technique's defaults with its quickSets (TechniqueInfo): every pass the defaults run, cheaply.
gl::ParamValues quickValues(const gl::TechniqueInfo& info)
{
    gl::ParamValues v(info.params);
    for (const std::string& kv : info.quickSets) {
        const auto eq = kv.find('=');
        if (eq != std::string::npos) v.set(info.params, kv.substr(0, eq), kv.substr(eq + 1));
    }
    return v;
}

struct Tally {
    std::set<std::string> checked, undeclared; // "technique/pass"
};

// Holds the passes of the frame just rendered (the timers keep that frame only) to their declarations.
void checkFrame(const std::string& technique, int frame, gl::Renderer& r, Tally& tally)
{
    for (const gl::PassStat& p : r.timers().stats()) {
        const std::string name = technique + "/" + p.pass;
        SCOPED_TRACE(name + ", frame " + std::to_string(frame));
        const gl::PassWork& w = p.work;
        bool declared = false;
        if (w.expectedComputeInvocations) {
            declared = true;
            EXPECT_EQ(w.computeInvocations, *w.expectedComputeInvocations)
                << "compute invocations counted by the driver vs. declared (x"
                << w.computeInvocations / std::max(*w.expectedComputeInvocations, 1.0) << ")";
        }
        if (w.expectedFragmentInvocations) {
            declared = true;
            const double pixels = *w.expectedFragmentInvocations, most = w.expectedFragmentInvocationsAtMost;
            EXPECT_GE(w.fragmentInvocations, pixels) << "fewer fragment invocations than the declared pixels";
            EXPECT_LE(w.fragmentInvocations, most)
                << "more fragment invocations than the declared pixels' 4x4 blocks and their diagonal (" << pixels
                << " pixels, x" << w.fragmentInvocations / std::max(pixels, 1.0) << ")";
        }
        (declared ? tally.checked : tally.undeclared).insert(name);
    }
}

// Every technique renders cornell-spot for three frames (the first builds what later frames reuse; the
// later ones are still frames, which accumulate), each frame checked on its own; `rsm` also runs with its
// indirect light at half resolution (the joint upsample), `hisr` with its gather as compute.
TEST_F(InvocationsTest, EveryDeclaredPassRunsTheInvocationsItDeclares)
{
    if (!gl::hasGlExtension("GL_ARB_pipeline_statistics_query"))
        GTEST_SKIP() << "the driver counts no invocations (GL_ARB_pipeline_statistics_query)";
    const core::Scene scene = core::makeCornell("cornell-spot");
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("shadow.size", 64);
    Tally tally;
    for (const gl::TechniqueInfo& info : gl::techniques()) {
        gl::Renderer r(scene, info.name, frameValues, quickValues(info), kWidth, kHeight);
        for (int frame = 0; frame < 3; ++frame) {
            if (info.name == "rsm" && frame == 2) r.setIndirectScale(2);
            r.timers().clear();
            r.renderFrame(true);
            checkFrame(info.name, frame, r, tally);
        }
    }
    // The multires gather in its other form, a compute dispatch over the list of valid fragments (the
    // default on llvmpipe is the stencilled quad, which declares nothing).
    {
        const gl::TechniqueInfo& info = gl::findTechnique("hisr");
        gl::ParamValues values = quickValues(info);
        values.set(info.params, "gather", "compute");
        gl::Renderer r(scene, info.name, frameValues, values, kWidth, kHeight);
        r.renderFrame(true);
        checkFrame("hisr(gather=compute)", 0, r, tally);
    }
    std::string checked, undeclared;
    for (const std::string& n : tally.checked) checked += " " + n;
    for (const std::string& n : tally.undeclared)
        if (!tally.checked.count(n)) undeclared += " " + n;
    std::printf("[ declared ] %zu passes hold to the invocations they declare:%s\n", tally.checked.size(),
                checked.c_str());
    std::printf("[ none     ] passes that declare no invocations (rasterised geometry, data-dependent work):%s\n",
                undeclared.c_str());
    EXPECT_FALSE(tally.checked.empty()) << "no pass declares its invocations";
}

} // namespace
} // namespace bounce
