// The light-path selections against each other on a box room with a block (occlusion, colour
// bleeding): direct <= onebounce <= full; onebounce-indirect == onebounce - direct and
// onebounce-novis-indirect >= onebounce-indirect (statistically, from the renders' own variance
// estimates); without the block the room is convex and ignoring visibility changes nothing.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "tests/ref/test_scenes.h"

namespace {

using namespace bounce;
using namespace bounce::testing;
using ref::LightPaths;

constexpr int kSize = 24;

ref::RenderResult renderRoom(const core::Scene& s, LightPaths paths, int spp, std::uint64_t seed = 3)
{
    return ref::render(s, s.camera, settings(paths, kSize, spp, seed));
}

TEST(LightPaths, NamesRoundTripAndUnknownNamesListTheAllowedOnes)
{
    for (const std::string& name : ref::lightPathsNames())
        EXPECT_EQ(ref::lightPathsName(ref::parseLightPaths(name)), name);
    EXPECT_EQ(ref::lightPathsNames().size(), 6u);
    try {
        ref::parseLightPaths("twobounce");
        FAIL();
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("twobounce"), std::string::npos);
        for (const char* n :
             {"direct", "onebounce", "onebounce-novis", "onebounce-indirect", "onebounce-novis-indirect", "full"})
            EXPECT_NE(what.find(n), std::string::npos) << n;
    }
}

TEST(LightPaths, BadSettingsThrow)
{
    const core::Scene s = boxRoom(true);
    ref::RenderSettings r = settings(LightPaths::Direct, 8, 0); // neither spp nor a noise target
    EXPECT_THROW(ref::render(s, s.camera, r), std::invalid_argument);
    r.spp = 1;
    r.width = 0;
    EXPECT_THROW(ref::render(s, s.camera, r), std::invalid_argument);
    r.width = 8;
    r.targetNoise = -1.0;
    EXPECT_THROW(ref::render(s, s.camera, r), std::invalid_argument);
    core::Scene broken = s;
    broken.meshes[0].indices.push_back(99);
    EXPECT_THROW(ref::render(broken, s.camera, settings(LightPaths::Direct, 8, 1)), std::invalid_argument);
}

TEST(LightPaths, OrderedAndAdditive)
{
    const core::Scene s = boxRoom(true);
    const ref::RenderResult direct = renderRoom(s, LightPaths::Direct, 32);
    const ref::RenderResult one = renderRoom(s, LightPaths::OneBounce, 32);
    const ref::RenderResult full = renderRoom(s, LightPaths::Full, 32);
    const ref::RenderResult indirect = renderRoom(s, LightPaths::OneBounceIndirect, 32);
    const double mDirect = imageMean(direct.image), mOne = imageMean(one.image), mFull = imageMean(full.image);
    const double seDirect = imageMeanStdErr(direct.variance), seOne = imageMeanStdErr(one.variance);
    const double seFull = imageMeanStdErr(full.variance), seIndirect = imageMeanStdErr(indirect.variance);
    EXPECT_GT(mOne - mDirect, 5.0 * std::hypot(seOne, seDirect));
    EXPECT_GT(mFull - mOne, 5.0 * std::hypot(seFull, seOne));
    // onebounce-indirect is exactly the L(D|G){2}E part of onebounce.
    EXPECT_NEAR(imageMean(indirect.image), mOne - mDirect,
                5.0 * std::sqrt(seIndirect * seIndirect + seOne * seOne + seDirect * seDirect));
    // Per pixel, on average over the image: direct <= onebounce <= full holds for nearly every pixel
    // (the exceptions are noise).
    int orderedPixels = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const auto lum = [&](const core::Image& im) {
                const glm::vec3 v = im.at(x, y);
                return v.x + v.y + v.z;
            };
            orderedPixels += lum(direct.image) <= lum(one.image) * 1.05f + 1e-6f &&
                             lum(one.image) <= lum(full.image) * 1.05f + 1e-6f;
        }
    EXPECT_GT(orderedPixels, kSize * kSize * 9 / 10);
    for (const ref::RenderResult* r : {&direct, &one, &full, &indirect}) EXPECT_EQ(r->nonFiniteSamples, 0u);
}

TEST(LightPaths, IgnoringVisibilityOnlyAddsLight)
{
    // With the block, some x2 hidden from x1 now contribute: more light, never less.
    const core::Scene s = boxRoom(true);
    const ref::RenderResult vis = renderRoom(s, LightPaths::OneBounceIndirect, 32);
    const ref::RenderResult novis = renderRoom(s, LightPaths::OneBounceNoVisIndirect, 32);
    const double se = std::hypot(imageMeanStdErr(vis.variance), imageMeanStdErr(novis.variance));
    EXPECT_GT(imageMean(novis.image) - imageMean(vis.image), 3.0 * se);
    // onebounce-novis = direct + onebounce-novis-indirect.
    const ref::RenderResult direct = renderRoom(s, LightPaths::Direct, 32);
    const ref::RenderResult whole = renderRoom(s, LightPaths::OneBounceNoVis, 32);
    EXPECT_NEAR(imageMean(whole.image), imageMean(direct.image) + imageMean(novis.image),
                5.0 * std::sqrt(std::pow(imageMeanStdErr(whole.variance), 2) +
                                std::pow(imageMeanStdErr(direct.variance), 2) +
                                std::pow(imageMeanStdErr(novis.variance), 2)));
}

TEST(LightPaths, ConvexRoomNeedsNoVisibility)
{
    // Without the block the room is convex: every x2 is visible from every x1, so both estimators
    // compute the same integral (by different sampling: visible nearest hit against all crossings).
    const core::Scene s = boxRoom(true, false);
    const ref::RenderResult vis = renderRoom(s, LightPaths::OneBounceIndirect, 32);
    const ref::RenderResult novis = renderRoom(s, LightPaths::OneBounceNoVisIndirect, 32);
    const double se = std::hypot(imageMeanStdErr(vis.variance), imageMeanStdErr(novis.variance));
    EXPECT_NEAR(imageMean(novis.image), imageMean(vis.image), 5.0 * se);
}

TEST(LightPaths, PointLitRoomOrdered)
{
    // Punctual lights go through next-event estimation only (no MIS partner): the same ordering holds,
    // direct < onebounce < full on the image mean (each gap beyond 5 standard errors) and per pixel for
    // nearly every pixel, and onebounce-indirect is onebounce less direct.
    const core::Scene s = boxRoom(false);
    const ref::RenderResult direct = renderRoom(s, LightPaths::Direct, 8);
    const ref::RenderResult one = renderRoom(s, LightPaths::OneBounce, 16);
    const ref::RenderResult full = renderRoom(s, LightPaths::Full, 16);
    const ref::RenderResult indirect = renderRoom(s, LightPaths::OneBounceIndirect, 16);
    const double mDirect = imageMean(direct.image), mOne = imageMean(one.image), mFull = imageMean(full.image);
    const double seDirect = imageMeanStdErr(direct.variance), seOne = imageMeanStdErr(one.variance);
    const double seFull = imageMeanStdErr(full.variance);
    EXPECT_GT(mDirect, 0.0);
    EXPECT_GT(mOne - mDirect, 5.0 * std::hypot(seOne, seDirect)) << "one bounce adds light";
    EXPECT_GT(mFull - mOne, 5.0 * std::hypot(seFull, seOne)) << "more bounces add light";
    EXPECT_NEAR(imageMean(indirect.image), mOne - mDirect,
                5.0 * std::sqrt(std::pow(imageMeanStdErr(indirect.variance), 2) + seOne * seOne + seDirect * seDirect));
    int orderedPixels = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const auto lum = [&](const core::Image& im) {
                const glm::vec3 v = im.at(x, y);
                return v.x + v.y + v.z;
            };
            orderedPixels += lum(direct.image) <= lum(one.image) * 1.05f + 1e-6f &&
                             lum(one.image) <= lum(full.image) * 1.05f + 1e-6f;
        }
    EXPECT_GT(orderedPixels, kSize * kSize * 9 / 10);
    for (const ref::RenderResult* r : {&direct, &one, &full, &indirect}) EXPECT_EQ(r->nonFiniteSamples, 0u);
}

} // namespace
