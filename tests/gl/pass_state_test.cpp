// PassState::apply() sets every piece of fixed-function state it holds: a pass that applies the
// defaults after a pass that changed everything sees the defaults, read back from GL itself.
#include <gtest/gtest.h>

#include "gl/gl.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/pass_state.h"
#include "gl/resource/texture.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

class PassStateTest : public GlTest {};

int getInt(unsigned pname)
{
    int v = 0;
    glGetIntegerv(pname, &v);
    return v;
}

TEST_F(PassStateTest, DefaultsUndoEverythingThePreviousPassSet)
{
    gl::Texture colour = gl::Texture::create2D("test.colour", GL_RGBA8, 3, 5);
    gl::Framebuffer fbo("test.fbo");
    fbo.attach(GL_COLOR_ATTACHMENT0, colour);

    gl::PassState changed = gl::PassState::fullscreen(fbo, 3, 5);
    changed.depthTest = true;
    changed.depthFunc = GL_GREATER;
    changed.depthWrite = false;
    changed.stencil = {true, GL_EQUAL, 3, 0x0F, 0x01, GL_DECR, GL_DECR, GL_DECR};
    changed.blend = true;
    changed.blendSrc = GL_SRC_ALPHA;
    changed.blendDst = GL_ONE_MINUS_SRC_ALPHA;
    changed.blendEquation = GL_MAX;
    changed.colorMask = glm::bvec4(false, true, false, true);
    changed.cull = true;
    changed.cullFace = GL_FRONT;
    changed.multisample = true;
    changed.apply();
    EXPECT_EQ(getInt(GL_FRAMEBUFFER_BINDING), int(fbo.id()));
    EXPECT_EQ(getInt(GL_STENCIL_FUNC), GL_EQUAL);
    EXPECT_EQ(getInt(GL_BLEND_EQUATION_RGB), GL_MAX);
    glEnable(GL_SCISSOR_TEST); // state a pass set by hand, outside PassState

    gl::PassState plain;
    plain.viewport = {0, 0, 2, 2};
    plain.apply();
    EXPECT_EQ(getInt(GL_FRAMEBUFFER_BINDING), 0);
    int vp[4];
    glGetIntegerv(GL_VIEWPORT, vp);
    EXPECT_EQ(vp[2], 2);
    EXPECT_EQ(vp[3], 2);
    EXPECT_FALSE(glIsEnabled(GL_DEPTH_TEST));
    EXPECT_EQ(getInt(GL_DEPTH_FUNC), GL_LESS);
    EXPECT_EQ(getInt(GL_DEPTH_WRITEMASK), GL_TRUE);
    EXPECT_FALSE(glIsEnabled(GL_STENCIL_TEST));
    EXPECT_EQ(getInt(GL_STENCIL_FUNC), GL_ALWAYS);
    EXPECT_EQ(getInt(GL_STENCIL_VALUE_MASK), 0xFF);
    EXPECT_EQ(getInt(GL_STENCIL_WRITEMASK), 0xFF);
    EXPECT_EQ(getInt(GL_STENCIL_PASS_DEPTH_PASS), GL_KEEP);
    EXPECT_FALSE(glIsEnabled(GL_BLEND));
    EXPECT_EQ(getInt(GL_BLEND_SRC_RGB), GL_ONE);
    EXPECT_EQ(getInt(GL_BLEND_EQUATION_RGB), GL_FUNC_ADD);
    GLboolean mask[4];
    glGetBooleanv(GL_COLOR_WRITEMASK, mask);
    for (GLboolean m : mask) EXPECT_TRUE(m);
    EXPECT_FALSE(glIsEnabled(GL_CULL_FACE));
    EXPECT_EQ(getInt(GL_CULL_FACE_MODE), GL_BACK);
    EXPECT_FALSE(glIsEnabled(GL_MULTISAMPLE));
    EXPECT_FALSE(glIsEnabled(GL_SCISSOR_TEST));
}

} // namespace
} // namespace bounce
