// The GoogleTest fixture for GL tests: one context per test suite (OSMesa unless BOUNCE_TEST_BACKEND says
// egl, osmesa or glfw), current in every test, and any GL error or high-severity debug message during a
// test fails it; new GL storage is poisoned. Derive a suite from it: `class FrameTest : public GlTest {};`.
#pragma once

#include <cstdlib>
#include <exception>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "gl/context/context.h"
#include "gl/debug.h"
#include "gl/resource/allocations.h"

class GlTest : public ::testing::Test {
public:
    static void SetUpTestSuite()
    {
        // New GL storage poisoned (gl/resource/allocations.h): llvmpipe hands out zeros where a GPU
        // driver hands out whatever the memory held, so a pass reading what no pass wrote fails here too.
        bounce::gl::setPoisonNewStorage(true);
        creationError().clear();
        const char* name = std::getenv("BOUNCE_TEST_BACKEND");
        bounce::gl::ContextOptions options;
        options.width = 64; // only a GLFW window uses these; tests render into framebuffers
        options.height = 64;
        options.visible = false;
        options.debug = true;
        // A suite without a context fails each of its tests with the reason (in SetUp) rather than
        // aborting the whole executable.
        try {
            context() = bounce::gl::Context::create(bounce::gl::parseBackend(name && *name ? name : "osmesa"), options);
        } catch (const std::exception& e) {
            creationError() = e.what();
        }
    }

    static void TearDownTestSuite() { context().reset(); }

protected:
    void SetUp() override
    {
        ASSERT_TRUE(context()) << "no GL context for this suite: " << creationError();
        context()->makeCurrent();
        bounce::gl::resetDebugErrors();
    }

    void TearDown() override
    {
        if (!context()) return;
        bounce::gl::checkGlError("the end of the test");
        const int count = bounce::gl::debugErrorCount();
        std::string messages;
        for (const bounce::gl::DebugMessage& m : bounce::gl::takeDebugErrors()) messages += "\n  " + m.text;
        EXPECT_EQ(count, 0) << "GL errors or high-severity debug messages during the test:" << messages;
    }

    static const bounce::gl::ContextInfo& glInfo() { return context()->info(); }

    static std::unique_ptr<bounce::gl::Context>& context()
    {
        static std::unique_ptr<bounce::gl::Context> c;
        return c;
    }

private:
    static std::string& creationError()
    {
        static std::string e;
        return e;
    }
};
