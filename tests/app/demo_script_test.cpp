// The demo's --script is parsed and checked without a window or GL (app/demo_script.h): each bad step is
// refused with a message naming the step and the problem, and set: is checked against the technique
// selected at that point of the script.
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "app/commands.h"
#include "app/demo_script.h"
#include "gl/technique/technique.h"

namespace {

using bounce::app::chooseDemoEdgeAA;
using bounce::app::chooseDemoTemporal;
using bounce::app::FrameBudgetState;
using bounce::app::nextFrameBudget;
using bounce::app::parseDemoScript;
using bounce::app::UsageError;
namespace gl = bounce::gl;

TEST(DemoScript, ParsesEveryVerbInOrder)
{
    const auto steps = parseDemoScript("wait:2,technique:isr,set:rsmSize=64,set:shadow.size=512,compare:rsm,"
                                       "screenshot:out/a.exr,quit,move:3,budget:50",
                                       "direct");
    ASSERT_EQ(steps.size(), 9u);
    EXPECT_EQ(steps[7].verb, "move");
    EXPECT_EQ(steps[8].arg, "50");
    EXPECT_EQ(steps[0].verb, "wait");
    EXPECT_EQ(steps[0].arg, "2");
    EXPECT_EQ(steps[2].verb, "set");
    EXPECT_EQ(steps[2].arg, "rsmSize=64");
    EXPECT_EQ(steps[3].arg, "shadow.size=512");
    EXPECT_EQ(steps[4].arg, "rsm");
    EXPECT_EQ(steps[6].verb, "quit");
    EXPECT_TRUE(parseDemoScript("", "direct").empty());
    EXPECT_TRUE(parseDemoScript(",,", "direct").empty()) << "empty items are skipped";
}

// A technique's parameter is valid only once that technique is selected; a frame parameter always.
TEST(DemoScript, SetFollowsTheSelectedTechnique)
{
    EXPECT_THROW(parseDemoScript("set:rsmSize=64,technique:isr", "direct"), UsageError);
    EXPECT_NO_THROW(parseDemoScript("technique:isr,set:rsmSize=64", "direct"));
    EXPECT_NO_THROW(parseDemoScript("set:rsmSize=64", "isr"));
    EXPECT_THROW(parseDemoScript("technique:direct,set:rsmSize=64", "isr"), UsageError);
    for (const char* technique : {"direct", "isr", "rsm"}) {
        EXPECT_NO_THROW(parseDemoScript("set:shadow.size=512,set:shadow.linear=0", technique)) << technique;
        EXPECT_TRUE(bounce::app::isFrameParam("shadow.size"));
        EXPECT_FALSE(bounce::app::isFrameParam("rsmSize"));
    }
}

TEST(DemoScript, BadStepsAreRefusedWithTheReason)
{
    const struct {
        const char* script;
        const char* says;
    } cases[] = {
        {"technique:nosuch", "unknown technique"},
        {"compare:nosuch", "unknown technique"},
        {"compare:", "unknown technique"},
        {"set:nokey=1", "unknown parameter"},
        {"set:shadow.size=3", "out of range"},
        {"set:shadow.size=big", "shadow.size"},
        {"set:shadow.pcf=1.5", "integer"},
        {"set:shadow.size", "key=value"},
        {"wait:x", "wait"},
        {"wait:-1", "wait"},
        {"wait:", "wait"},
        {"screenshot:", "file name"},
        {"move:0", "move"},
        {"move:x", "move"},
        {"budget:0", "budget"},
        {"budget:100001", "milliseconds"},
        {"jump:3", "unknown step"},
    };
    for (const auto& c : cases) {
        try {
            parseDemoScript(std::string("wait:1,") + c.script, "direct");
            ADD_FAILURE() << c.script << " was accepted";
        } catch (const UsageError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(c.says), std::string::npos) << c.script << ": " << what;
            EXPECT_NE(what.find(c.script), std::string::npos) << "the message names the step: " << what;
        }
    }
    EXPECT_THROW(parseDemoScript("wait:1", "nosuch"), UsageError) << "the initial technique is checked too";
}

// The demo's temporal default: on for a hardware renderer, off for a software rasterizer, and a --set of
// either parameter (whatever its value) leaves both as the command line made them.
TEST(DemoScript, TemporalReuseDefaultFollowsTheRendererUnlessSet)
{
    const auto choose = [](const std::vector<std::string>& sets, bool software) {
        gl::ParamValues v(gl::frameParams());
        chooseDemoTemporal(v, sets, software);
        return std::pair{v.getBool("temporal"), v.getBool("temporal.direct")};
    };
    EXPECT_EQ(choose({}, false), std::pair(true, true)) << "a GPU";
    EXPECT_EQ(choose({}, true), std::pair(false, false)) << "llvmpipe";
    EXPECT_EQ(choose({"shadow.size=512"}, false), std::pair(true, true)) << "another parameter";
    EXPECT_EQ(choose({"temporal=0"}, false), std::pair(false, false)) << "the user's temporal=0 on a GPU";
    EXPECT_EQ(choose({"temporal.direct=0"}, false), std::pair(false, false)) << "temporal.direct alone";
    // The values the command line parsed stay: the function sets nothing when either is named.
    gl::ParamValues set(gl::frameParams());
    set.setValue("temporal", 1.0);
    EXPECT_NE(chooseDemoTemporal(set, {"temporal=1"}, true).find("--set"), std::string::npos);
    EXPECT_TRUE(set.getBool("temporal"));
    EXPECT_FALSE(set.getBool("temporal.direct"));
}

// The moving frames' edge antialiasing likewise: on for a hardware renderer, off for a software rasterizer,
// and a --set of it leaves it as the command line made it.
TEST(DemoScript, EdgeAntialiasingDefaultFollowsTheRendererUnlessSet)
{
    const auto choose = [](const std::vector<std::string>& sets, bool software, bool before = false) {
        gl::ParamValues v(gl::frameParams());
        v.setValue("edgeAA", before ? 1.0 : 0.0);
        chooseDemoEdgeAA(v, sets, software);
        return v.getBool("edgeAA");
    };
    EXPECT_TRUE(choose({}, false)) << "a GPU";
    EXPECT_FALSE(choose({}, true)) << "llvmpipe";
    EXPECT_TRUE(choose({"temporal=0"}, false)) << "another parameter";
    EXPECT_FALSE(choose({"edgeAA=0"}, false)) << "the user's edgeAA=0 on a GPU";
    EXPECT_TRUE(choose({"edgeAA=1"}, true, true)) << "the user's edgeAA=1 on llvmpipe";
}

// The frame budget's steps (app/demo_script.h): over budget while moving, the points the budget added go
// before the indirect light coarsens; well under it, the indirect light comes back to full resolution
// before points are added, up to 8; a still frame is at full resolution with its points kept; neither
// setting moves where it may not (a technique that does not scale, points named on the command line).
TEST(DemoScript, FrameBudgetTradesPointsAndScaleInOrder)
{
    const auto step = [](FrameBudgetState s, double ms, bool moving = true, bool scales = true, bool points = true) {
        const FrameBudgetState n = nextFrameBudget(s, moving, ms, 100.0, scales, points);
        return std::pair{n.indirectScale, n.directSamples};
    };
    using P = std::pair<int, int>;
    EXPECT_EQ(step({1, 1}, 150), P(2, 1)) << "over budget with one point: coarser";
    EXPECT_EQ(step({1, 4}, 150), P(1, 2)) << "over budget: the added points go first";
    EXPECT_EQ(step({8, 1}, 150), P(8, 1)) << "over budget at 1/8 and one point: nothing left to give";
    EXPECT_EQ(step({4, 1}, 20), P(2, 1)) << "well under at 1/4: finer first";
    EXPECT_EQ(step({1, 1}, 20), P(1, 2)) << "well under at full resolution: two points";
    EXPECT_EQ(step({1, 4}, 20), P(1, 8));
    EXPECT_EQ(step({1, 8}, 20), P(1, 8)) << "at most 8 points";
    EXPECT_EQ(step({2, 4}, 60), P(2, 4)) << "between a quarter and the whole budget: as it was";
    EXPECT_EQ(step({4, 8}, 300, false), P(1, 8)) << "still: full resolution, the points kept for the next move";
    EXPECT_EQ(step({1, 1}, 150, true, false), P(1, 1)) << "a technique that does not scale, one point";
    EXPECT_EQ(step({1, 2}, 150, true, false), P(1, 1)) << "...gives its added points";
    EXPECT_EQ(step({1, 1}, 20, true, true, false), P(1, 1)) << "points named on the command line stay";
    EXPECT_EQ(step({1, 4}, 150, true, true, false), P(2, 4)) << "...over budget too";
    // From any start, a run of frames well under the budget ends at full resolution and 8 points, and a
    // run over it at 1/8 and one point: no state is left stranded.
    FrameBudgetState s{8, 1};
    for (int i = 0; i < 8; ++i) s = nextFrameBudget(s, true, 10, 100, true, true);
    EXPECT_EQ(P(s.indirectScale, s.directSamples), P(1, 8));
    for (int i = 0; i < 8; ++i) s = nextFrameBudget(s, true, 500, 100, true, true);
    EXPECT_EQ(P(s.indirectScale, s.directSamples), P(8, 1));
}

} // namespace
