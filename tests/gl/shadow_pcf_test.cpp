// Percentage-closer filtering from textureGather (glsl/common/shadow.glsl: percentageCloser) against the
// direct way, one filtered and compared texture lookup per tap (SHADOW_PCF_TAPS): the same visibility at
// every pixel, for every kind of shadow view (a spot's perspective layer, a point light's cube faces, a
// directional light's orthographic layer), kernel radii 0 to 2, bilinear and nearest taps.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "gl/context/context.h"
#include "gl/frame/bindings.h"
#include "gl/frame/frame.h"
#include "gl/gl.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/pass_state.h"
#include "gl/resource/program.h"
#include "tests/gl/cornell_directional.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class ShadowPcfTest : public GlTest {};

std::vector<float> visibility(gl::Frame& frame, const std::vector<gl::Define>& defines, int radius)
{
    gl::Program p =
        gl::Program::graphics("test.shadow", "frame/fullscreen.vert", "test/shadow_visibility.frag", defines);
    gl::Texture target = gl::Texture::create2D("test.shadow.visibility", GL_RGBA32F, frame.width(), frame.height());
    gl::Framebuffer fbo("test.shadow.fbo");
    fbo.attach(GL_COLOR_ATTACHMENT0, target);
    fbo.checkComplete();
    gl::PassState::fullscreen(fbo, frame.width(), frame.height()).apply();
    frame.bindGBuffer();
    frame.bindSceneData();
    frame.shadowMaps().setPcfUniforms(p, radius);
    p.set("lightIndex", 0);
    p.use();
    frame.drawFullscreen();
    const std::vector<float> rgba = target.readFloats(0, 4);
    std::vector<float> v(rgba.size() / 4);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = rgba[4 * i];
    return v;
}

TEST_F(ShadowPcfTest, GatheredKernelEqualsFilteredTaps)
{
    for (const char* name : {"cornell-spot", "cornell-point", "cornell-directional"}) {
        const core::Scene scene =
            std::string(name) == "cornell-directional" ? test::cornellDirectional() : core::makeCornell(name);
        for (bool linear : {true, false})
            for (int radius : {0, 1, 2}) {
                SCOPED_TRACE(std::string(name) + (linear ? " linear" : " nearest") + " r=" + std::to_string(radius));
                gl::FrameSettings s;
                s.width = 61; // odd sizes: no pixel lands on a texel grid by accident
                s.height = 47;
                s.shadowMapSize = 128; // coarse texels: wide penumbrae, many pixels between 0 and 1
                s.pcfLinear = linear;
                gl::Frame frame(scene, s);
                gl::PassTimers timers;
                frame.beginFrame();
                frame.renderShadowMaps(timers);
                frame.renderGBuffer(timers);
                timers.endFrame(false);
                const std::vector<float> gathered = visibility(frame, {}, radius);
                const std::vector<float> taps = visibility(frame, {{"SHADOW_PCF_TAPS", "1"}}, radius);
                float worst = 0.0f;
                int partial = 0, geometry = 0;
                for (std::size_t i = 0; i < taps.size(); ++i) {
                    if (taps[i] < 0.0f) continue;
                    ++geometry;
                    partial += taps[i] > 0.0f && taps[i] < 1.0f;
                    worst = std::max(worst, std::abs(gathered[i] - taps[i]));
                }
                std::printf("[ measured ] %s %s r=%d: %d pixels between lit and shadowed, largest difference %.2g\n",
                            name, linear ? "linear" : "nearest", radius, partial, worst);
                EXPECT_GT(geometry, 2000);
                if (radius > 0 || linear) {
                    EXPECT_GT(partial, radius == 0 ? 4 : 20) << "no penumbra: the comparison proves little";
                }
                // llvmpipe's bilinear weights are floats (measured: differences below 6e-7); a GPU's are 8-bit
                // fixed point, 1/256 steps, so a tap there may differ from the gathers' float weights by
                // 1/512 per texel.
                EXPECT_LT(worst, gl::softwareRasterizer() ? 1e-5f : 4e-3f);
            }
    }
}

} // namespace
} // namespace bounce
