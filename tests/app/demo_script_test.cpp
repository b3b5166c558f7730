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

} // namespace
