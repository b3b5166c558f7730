// Every pass against its bound (app/roofline.h): the bound is the pass's work at the machine's ceilings,
// checked here against hand-computed figures, and the ceilings' JSON round-trips and refuses nonsense.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "app/roofline.h"

namespace bounce::app {
namespace {

gl::Ceilings ceilings()
{
    gl::Ceilings c;
    c.renderer = "test renderer";
    c.size = 1024;
    c.fragmentGflops = 100; // 1e11 flop/s
    c.computeGflops = 50;
    c.fragmentGBps = 20; // 2e10 B/s
    c.computeImageGBps = 4;
    c.computeBufferGBps = 5; // the compute ceiling is the better of image and buffer
    c.fragmentGfetches = 2;
    c.computeGfetches = 1;
    c.fragmentGuniformWords = 5; // 5e9 words/s
    c.computeGuniformWords = 4;
    c.framebufferGBps = 30;
    c.mtrianglesPerSecond = 10; // 1e7 /s
    return c;
}

gl::PassStat pass(double ms, double fragments, double computes, double flops, double fetches, double bytes,
                  double triangles = 0.0)
{
    gl::PassStat p;
    p.pass = "p";
    p.medianMs = ms;
    p.work.fragmentInvocations = fragments;
    p.work.computeInvocations = computes;
    p.work.flops = flops;
    p.work.fetches = fetches;
    p.work.bytes = bytes;
    p.work.triangles = triangles;
    p.work.costDeclared = true;
    return p;
}

TEST(Roofline, FragmentPassBoundIsItsLargestTime)
{
    // 1e9 flops at 1e11/s = 10 ms; 1e8 fetches at 2e9/s = 50 ms; 4e8 bytes at 2e10 B/s = 20 ms.
    const auto b = passBound(pass(100.0, 1e6, 0, 1e9, 1e8, 4e8), ceilings());
    ASSERT_TRUE(b);
    EXPECT_NEAR(b->computeMs, 10.0, 1e-9);
    EXPECT_NEAR(b->fetchMs, 50.0, 1e-9);
    EXPECT_NEAR(b->memoryMs, 20.0, 1e-9);
    EXPECT_NEAR(b->boundMs, 50.0, 1e-9);
    EXPECT_EQ(b->limiter, "fetch");
    EXPECT_NEAR(b->efficiency, 0.5, 1e-12);
}

TEST(Roofline, ComputePassUsesComputeCeilings)
{
    // 1e9 flops at 5e10/s = 20 ms; 1e8 bytes at the better of 4 and 5 GB/s = 20 ms; ties go to compute.
    const auto b = passBound(pass(40.0, 0, 1e6, 1e9, 0, 1e8), ceilings());
    ASSERT_TRUE(b);
    EXPECT_NEAR(b->computeMs, 20.0, 1e-9);
    EXPECT_NEAR(b->memoryMs, 20.0, 1e-9);
    EXPECT_EQ(b->limiter, "compute");
    EXPECT_NEAR(b->efficiency, 0.5, 1e-12);
}

TEST(Roofline, TrianglesBoundAGeometryPass)
{
    // 1e5 triangles at 1e7/s = 10 ms, more than the 4 ms of its bytes.
    const auto b = passBound(pass(20.0, 1e5, 0, 0, 0, 8e7, 1e5), ceilings());
    ASSERT_TRUE(b);
    EXPECT_NEAR(b->setupMs, 10.0, 1e-9);
    EXPECT_EQ(b->limiter, "setup");
}

TEST(Roofline, UniformReadsBoundAGather)
{
    // A gather whose loop reads 1e9 uniform-block words: 200 ms at 5e9 words/s, more than its 1e9 flops
    // (10 ms) and its bytes (20 ms); in a compute pass the compute stage's rate (4e9: 250 ms).
    gl::PassStat p = pass(250.0, 1e6, 0, 1e9, 0, 4e8);
    p.work.uniformWords = 1e9;
    auto b = passBound(p, ceilings());
    ASSERT_TRUE(b);
    EXPECT_NEAR(b->uniformMs, 200.0, 1e-9);
    EXPECT_EQ(b->limiter, "uniform");
    EXPECT_NEAR(b->efficiency, 0.8, 1e-12);
    p.work.fragmentInvocations = 0;
    p.work.computeInvocations = 1e6;
    b = passBound(p, ceilings());
    ASSERT_TRUE(b);
    EXPECT_NEAR(b->uniformMs, 250.0, 1e-9);
}

TEST(Roofline, MixedStagesAreChargedTheirShares)
{
    // Half the invocations in each stage: 1e9 flops -> 5e8 at 1e11 (5 ms) + 5e8 at 5e10 (10 ms).
    const auto b = passBound(pass(30.0, 1e6, 1e6, 1e9, 0, 0), ceilings());
    ASSERT_TRUE(b);
    EXPECT_NEAR(b->computeMs, 15.0, 1e-9);
}

TEST(Roofline, NoBoundWithoutCountedInvocationsOrDeclaredCost)
{
    EXPECT_FALSE(passBound(pass(10.0, 0, 0, 1e9, 0, 0), ceilings())) << "no invocations counted";
    gl::PassStat undeclared = pass(10.0, 1e6, 0, 1e9, 0, 0);
    undeclared.work.costDeclared = false;
    EXPECT_FALSE(passBound(undeclared, ceilings()));
    EXPECT_FALSE(passBound(pass(0.0, 1e6, 0, 1e9, 0, 0), ceilings())) << "no measured time";
}

TEST(Roofline, RecordHasWorkAndBoundOnlyWithCeilings)
{
    const gl::PassStat p = pass(100.0, 1e6, 0, 1e9, 1e8, 4e8);
    const nlohmann::json without = passWorkJson(p, nullptr);
    EXPECT_EQ(without["fragmentInvocations"], 1e6);
    EXPECT_EQ(without["flops"], 1e9);
    EXPECT_FALSE(without.contains("boundMs"));
    const gl::Ceilings c = ceilings();
    const nlohmann::json with = passWorkJson(p, &c);
    EXPECT_DOUBLE_EQ(with["boundMs"].get<double>(), 50.0);
    EXPECT_DOUBLE_EQ(with["efficiency"].get<double>(), 0.5);
    EXPECT_EQ(with["limiter"], "fetch");
}

TEST(Roofline, CeilingsRoundTripAndRefuseNonsense)
{
    const gl::Ceilings c = ceilings();
    const gl::Ceilings back = gl::Ceilings::fromJson(c.toJson());
    EXPECT_EQ(back.toJson(), c.toJson());
    for (const char* key :
         {"fragmentGflops", "computeGBps", "mtrianglesPerSecond", "fragmentGuniformWords", "renderer"}) {
        nlohmann::json j = c.toJson();
        if (j.contains(key))
            j.erase(key);
        else
            j["computeImageGBps"] = -1.0; // computeGBps is derived: break a field it comes from
        EXPECT_THROW(gl::Ceilings::fromJson(j), std::invalid_argument) << key;
    }
    nlohmann::json nan = c.toJson();
    nan["fragmentGBps"] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(gl::Ceilings::fromJson(nan), std::invalid_argument);
    EXPECT_THROW(gl::Ceilings::fromJson(nlohmann::json::array()), std::invalid_argument);
}

TEST(Roofline, CachePathIsPerRenderer)
{
    EXPECT_NE(ceilingsCachePath("llvmpipe (LLVM 15.0.6, 256 bits)"), ceilingsCachePath("NVIDIA H100/PCIe/SSE2"));
    EXPECT_EQ(ceilingsCachePath("a"), ceilingsCachePath("a"));
}

} // namespace
} // namespace bounce::app
