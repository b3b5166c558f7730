#include "gl/resource/pass_state.h"

#include "gl/gl.h"
#include "gl/resource/framebuffer.h"

namespace bounce::gl {

namespace {
void enable(unsigned cap, bool on)
{
    if (on)
        glEnable(cap);
    else
        glDisable(cap);
}
} // namespace

PassState PassState::fullscreen(const Framebuffer& target, int width, int height)
{
    PassState s;
    s.framebuffer = target.id();
    s.viewport = {0, 0, width, height};
    return s;
}

void PassState::apply() const
{
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(viewport.x, viewport.y, viewport.z, viewport.w);
    enable(GL_DEPTH_TEST, depthTest);
    glDepthFunc(depthFunc);
    glDepthMask(depthWrite ? GL_TRUE : GL_FALSE);
    enable(GL_STENCIL_TEST, stencil.test);
    glStencilFunc(stencil.func, stencil.ref, stencil.readMask);
    glStencilMask(stencil.writeMask);
    glStencilOp(stencil.stencilFail, stencil.depthFail, stencil.depthPass);
    enable(GL_BLEND, blend);
    glBlendFunc(blendSrc, blendDst);
    glBlendEquation(blendEquation);
    glColorMask(colorMask.x, colorMask.y, colorMask.z, colorMask.w);
    enable(GL_CULL_FACE, cull);
    glCullFace(cullFace);
    enable(GL_POLYGON_OFFSET_FILL, polygonOffset != glm::vec2(0.0f));
    glPolygonOffset(polygonOffset.x, polygonOffset.y);
    enable(GL_MULTISAMPLE, multisample);
    enable(GL_SAMPLE_SHADING, sampleShading);
    enable(GL_SCISSOR_TEST, scissor);
    if (scissor) glScissor(viewport.x, viewport.y, viewport.z, viewport.w);
}

} // namespace bounce::gl
