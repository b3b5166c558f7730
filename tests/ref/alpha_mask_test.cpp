// Alpha-masked materials in the path tracer: Embree's filter function lets every kind of ray (closest
// hit, occlusion, all hits) through the holes of a MASK material and stops it on the opaque part, and a
// directional light through the masked quad of tests/alpha_mask_scene.h lights the floor under its
// transparent half exactly (E rho / pi) and not under its opaque half.
#include <cmath>

#include <gtest/gtest.h>

#include "ref/embree_scene.h"
#include "tests/alpha_mask_scene.h"
#include "tests/ref/test_scenes.h"

namespace {

using namespace bounce;
using namespace bounce::testing;

constexpr float kAlbedo = 0.5f;
constexpr float kIrradiance = 3.0f; // W/m^2

// A 2 m floor at y = 0 under the masked quad, a camera at 1.2 m between them looking down, and the sun
// straight above.
core::Scene floorUnderMask()
{
    core::Scene s;
    const auto floor = addMaterial(s, lambertian(glm::vec3(kAlbedo)));
    addHorizontalSquare(s, floor, 0.0f, 1.0f, true);
    addMaskedQuad(s);
    core::Light sun;
    sun.type = core::LightType::Directional;
    sun.direction = {0.0f, -1.0f, 0.0f};
    sun.intensity = glm::vec3(kIrradiance);
    s.lights.push_back(sun);
    s.camera = cameraLookingDown({0.0f, 1.2f, 0.0f}, 60.0f * core::kPi / 180.0f);
    return s;
}

TEST(AlphaMaskRays, RaysPassTheHolesAndStopOnTheOpaquePart)
{
    const core::Scene s = floorUnderMask();
    const ref::EmbreeScene e(s, true);
    std::uint64_t rays = 0;
    const glm::vec3 down(0.0f, -1.0f, 0.0f), up(0.0f, 1.0f, 0.0f);
    ref::Hit hit;
    // Through the transparent half (x < 0): the floor, 3 m below.
    ASSERT_TRUE(e.intersect({-0.25f, 3.0f, 0.1f}, down, 0.0f, 10.0f, hit, rays));
    EXPECT_EQ(hit.mesh, 0u);
    EXPECT_NEAR(hit.t, 3.0f, 1e-5f);
    // Onto the opaque half: the quad, 1.5 m below.
    ASSERT_TRUE(e.intersect({0.25f, 3.0f, 0.1f}, down, 0.0f, 10.0f, hit, rays));
    EXPECT_EQ(hit.mesh, 1u);
    EXPECT_NEAR(hit.t, 1.5f, 1e-5f);
    // Shadow rays from the floor, both sides of the quad alike (it is double-sided).
    EXPECT_FALSE(e.occluded({-0.25f, 0.0f, -0.3f}, up, 1e-4f, 10.0f, rays));
    EXPECT_TRUE(e.occluded({0.25f, 0.0f, -0.3f}, up, 1e-4f, 10.0f, rays));
    EXPECT_FALSE(e.occluded({-0.25f, 3.0f, -0.3f}, down, 0.0f, 2.0f, rays));
    EXPECT_TRUE(e.occluded({0.25f, 3.0f, -0.3f}, down, 0.0f, 2.0f, rays));
    // Every crossing: the hole is not one.
    std::vector<ref::Hit> hits;
    e.allHits({-0.25f, 3.0f, 0.2f}, down, 0.0f, 10.0f, hits, rays);
    EXPECT_EQ(hits.size(), 1u);
    e.allHits({0.25f, 3.0f, 0.2f}, down, 0.0f, 10.0f, hits, rays);
    EXPECT_EQ(hits.size(), 2u);
    // The same quad opaque blocks both halves.
    core::Scene opaque = s;
    opaque.materials.back().alphaMode = core::AlphaMode::Opaque;
    const ref::EmbreeScene o(opaque);
    EXPECT_TRUE(o.occluded({-0.25f, 0.0f, -0.3f}, up, 1e-4f, 10.0f, rays));
}

// The floor seen between the quad and the floor: lit through the hole (x < 0 under the quad) at the
// closed form E rho / pi, black under the opaque half (x > 0).
TEST(AlphaMaskRays, SunThroughTheMaskLightsOnlyUnderTheHole)
{
    const core::Scene s = floorUnderMask();
    constexpr int kSize = 32;
    const ref::RenderResult r = ref::render(s, s.camera, settings(ref::LightPaths::Direct, kSize, 4));
    double hole = 0.0, shadow = 0.0;
    int holeCount = 0, shadowCount = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec3 d = s.camera.rayDirection(x + 0.5f, y + 0.5f, kSize, kSize);
            const glm::vec3 p = s.camera.position + d * (s.camera.position.y / -d.y);
            if (std::abs(p.z) > 0.4f || std::abs(p.x) < 0.06f || std::abs(p.x) > 0.44f) continue; // away from edges
            const double v = r.image.at(x, y).y;
            (p.x < 0.0f ? hole : shadow) += v;
            ++(p.x < 0.0f ? holeCount : shadowCount);
        }
    ASSERT_GT(holeCount, 50);
    ASSERT_GT(shadowCount, 50);
    const double expected = kIrradiance * kAlbedo / core::kPi; // no noise: one sun, one shadow ray a sample
    EXPECT_NEAR(hole / holeCount, expected, 1e-4 * expected);
    EXPECT_EQ(shadow, 0.0);
}

} // namespace
