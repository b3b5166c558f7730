// The frame against physics: direct light from the canonical Cornell variants checked pixel by pixel
// against closed forms evaluated on the CPU, with what each pixel sees decided by an independent CPU
// ray caster (tests/gl/cpu_raycast.h), not by the renderer's own G-buffer.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/cornell.h"
#include "gl/context/context.h"
#include "gl/gl.h"
#include "gl/renderer.h"
#include "gl/resource/buffer.h"
#include "gl/resource/dispatch.h"
#include "gl/resource/program.h"
#include "tests/gl/cpu_raycast.h"
#include "tests/gl/gl_test_fixture.h"
#include "tests/gl/photon_test_scenes.h"
#include "tests/gl/point_test_util.h"

namespace bounce {
namespace {

using test::raycast;
using test::visible;

constexpr int kSize = 64;

core::Image renderDirect(const core::Scene& scene, int width, int height, bool hardShadows)
{
    gl::ParamValues frameValues(gl::frameParams());
    if (hardShadows) {
        frameValues.setValue("shadow.pcf", 0);
        frameValues.setValue("shadow.linear", 0);
    }
    // Every view at 1024^2 (no side from the footprint): the 5 mm of robustVisibility are a few texels.
    frameValues.setValue("shadow.size", 1024);
    frameValues.setValue("shadow.footprint", 0);
    gl::Renderer r(scene, "direct", frameValues, gl::ParamValues(), width, height);
    r.renderFrame();
    return r.image();
}

// A point is "robustly" lit or shadowed when points 5 mm around it on the surface agree with it: pixels
// on a shadow edge are where shadow-map resolution, not physics, decides.
int robustVisibility(const core::Scene& scene, const glm::vec3& p, const glm::vec3& n, const glm::vec3& light)
{
    const glm::vec3 t = std::abs(n.y) < 0.9f ? glm::normalize(glm::cross(n, glm::vec3(0, 1, 0)))
                                             : glm::normalize(glm::cross(n, glm::vec3(1, 0, 0)));
    const glm::vec3 b = glm::cross(n, t);
    const bool centre = visible(scene, p, n, light);
    for (const glm::vec3& o : {t, -t, b, -b})
        if (visible(scene, p + 0.005f * o, n, light) != centre) return -1;
    return centre ? 1 : 0;
}

class FrameTest : public GlTest {};

// Direct light on the floor of cornell-spot equals albedo/pi * I cos(theta) / r^2 (PCF off). Tolerance
// 0.5% relative: the G-buffer stores albedo in half floats (relative error below 5e-4) and positions
// are rasterised at pixel centres exactly as the CPU rays are cast; the rest is float arithmetic.
TEST_F(FrameTest, SpotFloorMatchesInverseSquareCosineLaw)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    const core::Image img = renderDirect(scene, kSize, kSize, true);
    const core::Light& light = scene.lights.at(0);
    int checked = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec3 d = scene.camera.rayDirection(x + 0.5f, y + 0.5f, kSize, kSize);
            const auto hit = raycast(scene, scene.camera.position, d);
            if (!hit || std::abs(hit->position.y) > 1e-5f) continue; // floor only
            const glm::vec3 n(0, 1, 0);
            const glm::vec3 toLight = light.position - hit->position;
            const float r2 = glm::dot(toLight, toLight);
            const glm::vec3 wi = toLight / std::sqrt(r2);
            const float cosLight = glm::dot(-wi, light.direction);
            if (cosLight < std::cos(light.outerConeRad) + 0.02f) continue; // away from the cone's edge
            if (robustVisibility(scene, hit->position, n, light.position) != 1) continue;
            const glm::vec3 albedo = scene.materials[hit->material].baseColor;
            const glm::vec3 expected = albedo / core::kPi * light.intensity * (glm::dot(n, wi) / r2);
            const glm::vec3 got = img.at(x, y);
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(got[c], expected[c], 5e-3f * expected[c]) << "pixel " << x << "," << y << " channel " << c;
            ++checked;
        }
    EXPECT_GT(checked, 200) << "too few floor pixels were checked";
}

// The short block's shadow lies where the geometry puts it, and outside the spot cone it is dark.
TEST_F(FrameTest, ShadowAndConeWhereGeometrySays)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    const core::Image img = renderDirect(scene, kSize, kSize, true);
    const core::Light& light = scene.lights.at(0);
    int shadowed = 0, outside = 0, lit = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec3 d = scene.camera.rayDirection(x + 0.5f, y + 0.5f, kSize, kSize);
            const auto hit = raycast(scene, scene.camera.position, d);
            if (!hit) continue;
            glm::vec3 n = hit->geometricNormal;
            if (glm::dot(n, d) > 0.0f) n = -n;
            const glm::vec3 wi = glm::normalize(light.position - hit->position);
            const float cosLight = glm::dot(-wi, light.direction);
            const float lum = glm::dot(img.at(x, y), glm::vec3(1.0f / 3.0f));
            if (cosLight < std::cos(light.outerConeRad) - 0.02f) {
                EXPECT_EQ(lum, 0.0f) << "outside the cone, pixel " << x << "," << y;
                ++outside;
                continue;
            }
            if (cosLight < std::cos(light.outerConeRad) + 0.02f || glm::dot(n, wi) < 0.05f) continue;
            const int v = robustVisibility(scene, hit->position, n, light.position);
            if (v == 0) {
                EXPECT_EQ(lum, 0.0f) << "in the block's shadow, pixel " << x << "," << y;
                ++shadowed;
            } else if (v == 1) {
                EXPECT_GT(lum, 0.0f) << "lit, pixel " << x << "," << y;
                ++lit;
            }
        }
    EXPECT_GT(shadowed, 10);
    EXPECT_GT(outside, 100);
    EXPECT_GT(lit, 200);
}

// The position every technique reads is rebuilt from the eye depth (common/gbuffer.glsl). A fragment and a
// compute shader rebuild the very same bits for a pixel (photon mapping matches pixels to their cluster
// samples exactly), and the position lies on the surface that an independent CPU ray through the pixel's
// centre meets: at the scene's size and at a thousand times it, in a viewport of odd sizes.
TEST_F(FrameTest, RebuiltPositionSameInEveryStageAndOnTheSurface)
{
    constexpr int w = 37, h = 29;
    for (float k : {1.0f, 1000.0f}) {
        SCOPED_TRACE(k);
        const core::Scene scene = photontest::scaledScene(core::makeCornell("cornell-spot"), k);
        gl::Renderer r(scene, "direct", gl::ParamValues(gl::frameParams()), gl::ParamValues(), w, h);
        r.renderFrame();
        const std::vector<float> fragment = r.frame().readPositions(); // RGBA, GL rows (row 0 at the bottom)
        gl::Buffer out("test.gbuffer.positions", std::size_t(w * h) * sizeof(glm::vec4));
        gl::Program program =
            gl::Program::compute("test.gbuffer.positions", "test/gbuffer_positions.comp", r.frame().gbufferDefines());
        r.frame().bindGBuffer();
        out.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
        program.set("size", glm::ivec2(w, h));
        gl::dispatchCompute(program, {w, h, 1}, {8, 8, 1});
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        const std::vector<glm::vec4> compute = out.download<glm::vec4>();
        int differ = 0, surface = 0, onSurface = 0;
        float worst = 0.0f;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const float* f = &fragment[std::size_t(y * w + x) * 4];
                const glm::vec4& c = compute[std::size_t(y * w + x)];
                differ += std::memcmp(f, &c, sizeof c) != 0;
                if (f[3] == 0.0f) continue;
                // Image rows go down; GL rows go up.
                const glm::vec3 d = scene.camera.rayDirection(x + 0.5f, (h - 1 - y) + 0.5f, w, h);
                const auto hit = raycast(scene, scene.camera.position, d);
                if (!hit) continue;
                ++surface;
                const float gap = glm::length(glm::vec3(f[0], f[1], f[2]) - hit->position) / hit->t;
                worst = std::max(worst, gap);
                onSurface += gap <= 1e-5f; // float rounding of depth and ray: a few 1e-7 of the distance
            }
        EXPECT_EQ(differ, 0) << "pixels whose fragment and compute positions differ in any bit";
        EXPECT_GT(surface, w * h / 2);
        // Pixels on a silhouette may see another surface than the CPU ray: at most a few.
        EXPECT_GE(onSurface, surface - surface / 50) << "largest gap " << worst << " of the distance";
        std::printf("[ measured ] scale %g: %d of %d positions within 1e-5 of the distance from the ray cast's, "
                    "largest %.3g; %d differ between stages\n",
                    double(k), onSurface, surface, double(worst), differ);
    }
}

// The emitter of cornell-area is seen with exactly its radiance (17, 12, 4): half floats hold these
// integers exactly, and the emitter reflects nothing.
TEST_F(FrameTest, AreaEmitterSeenWithItsRadiance)
{
    const core::Scene scene = core::makeCornell("cornell-area");
    const core::Image img = renderDirect(scene, kSize, kSize, false);
    int seen = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec3 d = scene.camera.rayDirection(x + 0.5f, y + 0.5f, kSize, kSize);
            const auto hit = raycast(scene, scene.camera.position, d);
            if (!hit || !scene.materials[hit->material].isEmissive()) continue;
            EXPECT_EQ(img.at(x, y), glm::vec3(17.0f, 12.0f, 4.0f)) << "pixel " << x << "," << y;
            ++seen;
        }
    EXPECT_GT(seen, 4);
}

// Deforming geometry (Frame::moveVertices) against the deformed scene loaded as it is: cornell-area and
// cornell-spot scaled by (1.2, 1.1, 0.9) after a first frame render the direct light of the scene made with
// those vertices: the G-buffer, the shadow maps' views fitted to the new bounds, the area lights and their
// shadow cube where the emitter now is, to the bit. Measured with the area light left where it was: the
// pixels of cornell-area differ by 11% of the image's mean on average. Then flattened onto a plane.
TEST_F(FrameTest, MovedVerticesRenderAsTheMovedScene)
{
    const glm::vec3 scale(1.2f, 1.1f, 0.9f);
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("shadow.size", 256);
    for (const char* name : {"cornell-area", "cornell-spot"}) {
        SCOPED_TRACE(name);
        const core::Scene scene = core::makeCornell(name);
        const testing::MovedVertices moved = testing::scaledVertices(scene, scale);
        const core::Scene loaded = testing::withVertices(scene, moved);
        // Direct light, and on cornell-spot reflective shadow maps at half resolution (Renderer::setIndirectScale,
        // the frame's coarse targets first drawn after the move): the coarse G-buffer sees the moved geometry.
        const bool coarse = std::string(name) == "cornell-spot";
        const std::string technique = coarse ? "rsm" : "direct";
        const gl::ParamValues values(gl::findTechnique(technique).params);
        gl::Renderer deformed(scene, technique, frameValues, values, kSize, kSize);
        deformed.renderFrame();
        ASSERT_TRUE(deformed.moveVertices(moved.positions, moved.normals));
        if (coarse) deformed.setIndirectScale(2);
        deformed.renderFrame();
        gl::Renderer fresh(loaded, technique, frameValues, values, kSize, kSize);
        if (coarse) fresh.setIndirectScale(2);
        fresh.renderFrame();
        const core::Image a = deformed.image(), b = fresh.image();
        double largest = 0.0, sum = 0.0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                for (int c = 0; c < 3; ++c) {
                    largest = std::max(largest, double(std::abs(a.at(x, y)[c] - b.at(x, y)[c])));
                    sum += b.at(x, y)[c];
                }
        const double mean = sum / (3.0 * kSize * kSize);
        std::printf("[ moved    ] %s, %s: largest difference %.3g (mean %.3g)\n", name, technique.c_str(), largest,
                    mean);
        EXPECT_LE(largest, 1e-4 * mean);

        // The hard case of a scene flattened onto the plane x = 0: every emitter degenerate, no area light left (the
        // direct pass loses AREA_LIGHTS), and what is drawn stays finite and non-negative.
        const testing::MovedVertices flat = testing::scaledVertices(scene, {0.0f, 1.0f, 1.0f});
        ASSERT_TRUE(deformed.moveVertices(flat.positions, flat.normals));
        deformed.renderFrame();
        EXPECT_EQ(int(deformed.frame().gpuScene().lights().size()), deformed.frame().gpuScene().punctualLightCount());
        EXPECT_TRUE(testing::allFiniteNonNegative(deformed.image()));
    }
}

// A spot's or point light's map sized from its footprint (gl/frame/shadow_maps.h) is rendered into the
// corner of a larger layer and read through a matrix that maps into it, taps kept inside: it must read as
// a whole layer of that side does. At 64x64 every view's footprint asks for less than the floor of 256
// texels; the layers of 1024 then hold 256^2 corners, against layers of 256 used whole (footprint 0). A
// moving frame and three still frames (the maps shifted by sub-texel offsets of their own texels).
// Measured: at most 10 of 12288 values differ, by 4e-7 of the mean, in the moving frame (its filtered
// taps); the still frames not at all. A shift of the whole layer's texels instead of the view's own: 0.3-0.5%.
TEST_F(FrameTest, FootprintSizedMapReadsAsAWholeMapOfItsSide)
{
    for (const char* name : {"cornell-spot", "cornell-point"}) {
        const core::Scene scene = core::makeCornell(name);
        auto render = [&](int size, float footprint) {
            gl::ParamValues frameValues(gl::frameParams());
            frameValues.setValue("shadow.size", size);
            frameValues.setValue("shadow.footprint", footprint);
            gl::Renderer r(scene, "direct", frameValues, gl::ParamValues(), kSize, kSize);
            std::vector<core::Image> frames;
            for (int i = 0; i < 4; ++i) {
                r.renderFrame(false);
                frames.push_back(r.image());
            }
            for (int side : r.frame().shadowMaps().sides()) EXPECT_EQ(side, 256) << name;
            return frames;
        };
        const std::vector<core::Image> corner = render(1024, 2.0f), whole = render(256, 0.0f);
        for (std::size_t f = 0; f < corner.size(); ++f) {
            double diff = 0.0, sum = 0.0;
            int differ = 0;
            for (std::size_t i = 0; i < corner[f].rgb.size(); ++i) {
                const double d = std::abs(corner[f].rgb[i] - whole[f].rgb[i]);
                diff += d;
                sum += whole[f].rgb[i];
                differ += d > 1e-4 * (whole[f].rgb[i] + 1e-3) ? 1 : 0;
            }
            std::printf("[ measured ] %s frame %zu: %d of %zu values differ, mean difference %.3g of the mean\n", name,
                        f, differ, corner[f].rgb.size(), diff / sum);
            EXPECT_LT(diff, 1e-4 * sum) << name << " frame " << f;
            EXPECT_LT(differ, int(corner[f].rgb.size()) / 400) << name << " frame " << f;
        }
    }
}

// Invariants on every canonical variant and a viewport that is not a power of two: finite, non-negative.
TEST_F(FrameTest, FiniteNonNegativeOnEveryVariant)
{
    for (const char* name : {"cornell-area", "cornell-spot", "cornell-point", "cornell-point-ceiling"}) {
        const core::Scene scene = core::makeCornell(name);
        const core::Image img = renderDirect(scene, 33, 20, false);
        double sum = 0.0;
        for (float v : img.rgb) {
            ASSERT_TRUE(std::isfinite(v)) << name;
            ASSERT_GE(v, 0.0f) << name;
            sum += v;
        }
        EXPECT_GT(sum, 0.0) << name;
    }
}

} // namespace
} // namespace bounce
