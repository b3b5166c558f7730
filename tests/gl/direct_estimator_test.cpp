// One direct-light estimator per kind of light (glsl/common/lighting.glsl, addDirectLight): a pixel of the
// G-buffer and a ray's hit on the same surface point get the same direct light, for every kind of light and in
// both forms of the estimator (the moving frame's and the still frames'). glsl/test/direct_at_hits.comp,
// compiled as every consumer of the estimator is (DirectLitProgram: the frame's defines and uniforms), lights
// each pixel's surface twice after the frame rendered:
//   - from the G-buffer's point, normal and BRDF: the same as the frame's direct pass (direct.frag, a fragment
//     shader compiled apart) to float precision, emission included;
//   - at the hit of a ray cast from the camera to that point through the frame's BVH, its normal and BRDF
//     decoded from the scene (scene_hit.glsl) as the gathers decode theirs: the same light but for what the
//     G-buffer rounds (half-float albedo, 16-bit octahedral normals, the depth's position), which moves a
//     shadow map's tap across a shadow's edge at a few pixels.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "gl/frame/direct_lit_program.h"
#include "gl/gl.h"
#include "gl/renderer.h"
#include "gl/resource/buffer.h"
#include "gl/resource/dispatch.h"
#include "tests/gl/cornell_directional.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class DirectEstimatorTest : public GlTest {};

struct Case {
    std::string name;
    core::Scene scene;
    std::string areaShadows; // frame parameter shadow.area
};

float luminance(const glm::vec4& c)
{
    return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

// Renders `frames` frames (the first moving, the rest still) and compares, pixel by pixel, the frame's direct
// texture, the estimator at the G-buffer's points and at the rays' hits.
void expectSameLight(const Case& c, int frames)
{
    SCOPED_TRACE(c.name + ", " + std::to_string(frames) + " frames");
    constexpr int w = 37, h = 29; // odd, not powers of two
    gl::ParamValues frameValues(gl::frameParams());
    if (!c.areaShadows.empty()) frameValues.set(gl::frameParams(), "shadow.area", c.areaShadows);
    gl::Renderer r(c.scene, "direct", frameValues, gl::ParamValues(), w, h);
    for (int i = 0; i < frames; ++i) r.renderFrame();
    gl::Frame& frame = r.frame();

    const std::size_t n = std::size_t(w) * h;
    gl::Buffer asPixel("test.direct.asPixel", n * sizeof(glm::vec4));
    gl::Buffer lit("test.direct.lit", n * sizeof(glm::vec4));
    gl::Buffer atHits("test.direct.atHits", n * sizeof(glm::vec4));
    std::vector<gl::Define> defines = frame.gbufferDefines();
    for (const gl::Define& d : frame.rayCaster().defines()) defines.push_back(d);
    gl::DirectLitProgram programs("test.direct", "test/direct_at_hits.comp", defines);
    gl::Program& program = programs.forFrame(frame);
    frame.bindGBuffer();
    frame.bindSceneData();
    frame.rayCaster().bind();
    asPixel.bindBase(GL_SHADER_STORAGE_BUFFER, 7);
    lit.bindBase(GL_SHADER_STORAGE_BUFFER, 9);
    atHits.bindBase(GL_SHADER_STORAGE_BUFFER, 11);
    program.set("size", glm::ivec2(w, h));
    program.set("cameraPosition", frame.camera().position);
    gl::dispatchCompute(program, {w, h, 1}, {8, 8, 1});
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::vector<float> direct = frame.direct().readFloats(); // this frame's, before accumulation
    const std::vector<glm::vec4> pixel = asPixel.download<glm::vec4>();
    const std::vector<glm::vec4> gbuffer = lit.download<glm::vec4>();
    const std::vector<glm::vec4> hits = atHits.download<glm::vec4>();

    int surface = 0, samePixel = 0, hit = 0, sameHit = 0;
    float worstPixel = 0.0f;
    double sumGBuffer = 0.0, sumHits = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        if (pixel[i].w == 0.0f) continue;
        ++surface;
        const glm::vec4 d(direct[4 * i], direct[4 * i + 1], direct[4 * i + 2], 0.0f);
        const float a = luminance(d), b = luminance(pixel[i]);
        ASSERT_TRUE(std::isfinite(a) && std::isfinite(b) && a >= 0.0f && b >= 0.0f) << "pixel " << i;
        const float gap = std::abs(a - b) / std::max(a, 1e-6f);
        worstPixel = std::max(worstPixel, gap);
        samePixel += gap <= 1e-5f;
        if (hits[i].w == 0.0f) continue;
        ++hit;
        const float g = luminance(gbuffer[i]), t = luminance(hits[i]);
        sumGBuffer += g;
        sumHits += t;
        // The G-buffer's rounding: 2^-11 of the albedo, 1e-4 of the normal's direction.
        sameHit += std::abs(g - t) <= 2e-3f * std::max(g, t) + 1e-6f;
    }
    std::printf("[ measured ] %s, %d frames: %d of %d pixels as the direct pass within 1e-5 (largest %.3g); %d of %d "
                "hits as their pixel within 0.2%%, means %.6g / %.6g\n",
                c.name.c_str(), frames, samePixel, surface, double(worstPixel), sameHit, hit, sumHits, sumGBuffer);
    ASSERT_GT(surface, int(n) / 2);
    EXPECT_EQ(samePixel, surface) << "the direct pass and the estimator at its points differ; largest relative "
                                  << worstPixel;
    // Silhouettes (the ray meets another surface) and shadow edges: a few pixels.
    EXPECT_GE(hit, surface - surface / 20);
    EXPECT_GE(sameHit, hit - hit / 25) << "hits lit unlike the pixels at their points";
    EXPECT_NEAR(sumHits, sumGBuffer, 5e-3 * sumGBuffer);
}

std::vector<Case> everyKind()
{
    return {
        {"point", core::makeCornell("cornell-point"), ""},
        {"spot", core::makeCornell("cornell-spot"), ""},
        {"directional", test::cornellDirectional(), ""},
        {"area", core::makeCornell("cornell-area"), ""},
        {"area, pcss", core::makeCornell("cornell-area"), "pcss"},
        {"area, glossy", core::makeCornell("cornell-glossy"), ""},
    };
}

// The moving frame's form: every light kind, PCF, PCSS for the emitters when asked for.
TEST_F(DirectEstimatorTest, PixelAndRayHitGetTheSameLightInAMovingFrame)
{
    for (const Case& c : everyKind()) expectSameLight(c, 1);
}

// The still frames' form: the emitters sampled at this frame's point on each mesh, the glossy lobe over their
// rotated points, one shifted shadow tap, a directional light's cascades.
TEST_F(DirectEstimatorTest, PixelAndRayHitGetTheSameLightInAStillFrame)
{
    for (const Case& c : everyKind())
        if (c.areaShadows.empty()) expectSameLight(c, 3);
}

} // namespace
} // namespace bounce
