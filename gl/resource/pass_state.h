// The fixed-function state of one pass as one value: framebuffer, viewport, depth, stencil, blending,
// colour mask, culling, multisampling. apply() sets every piece of it, so a pass cannot inherit what the
// previous pass left behind (a stencil test, a colour mask, blending) and cannot leak its own into the
// next. Passes build theirs from the defaults below and change only what they need:
//
//     PassState s = PassState::fullscreen(fbo, width, height);
//     s.blend = true;                       // additive: GL_ONE, GL_ONE
//     s.apply();
#pragma once

#include <glm/glm.hpp>

namespace bounce::gl {

class Framebuffer;

struct StencilState {
    bool test = false;
    unsigned func = 0x0207; // GL_ALWAYS
    int ref = 0;
    unsigned readMask = 0xFF;
    unsigned writeMask = 0xFF;
    unsigned stencilFail = 0x1E00, depthFail = 0x1E00, depthPass = 0x1E00; // GL_KEEP
};

struct PassState {
    unsigned framebuffer = 0;        // 0: the default framebuffer
    glm::ivec4 viewport{0, 0, 1, 1}; // x, y, width, height
    bool scissor = false;            // the scissor test to the viewport (a clear then touches it only)
    bool depthTest = false;
    unsigned depthFunc = 0x0201; // GL_LESS
    bool depthWrite = true;
    StencilState stencil;
    bool blend = false;
    unsigned blendSrc = 1, blendDst = 1; // GL_ONE, GL_ONE (additive)
    unsigned blendEquation = 0x8006;     // GL_FUNC_ADD
    glm::bvec4 colorMask{true};
    bool cull = false;
    unsigned cullFace = 0x0405;    // GL_BACK
    glm::vec2 polygonOffset{0.0f}; // glPolygonOffset(factor, units) on filled polygons; (0, 0): off
    bool multisample = false;
    bool sampleShading = false; // per-sample fragment shading (stencil routing)

    // A pass over the whole of a target: its framebuffer and viewport, everything else default.
    static PassState fullscreen(const Framebuffer& target, int width, int height);
    void apply() const;
};

} // namespace bounce::gl
