// Indirect light computed at a coarser resolution, brought to the full frame by joint bilateral
// upsampling (the demo's frame budget: Frame::beginIndirect, gl::Renderer::setIndirectScale). Each
// full-resolution pixel blends the four nearest coarse pixels with their bilinear weights, keeping only
// those on the same surface as itself by its own G-buffer: eye depth within `depthTolerance` of its own
// (relative) and normals within `normalTolerance` (1 - cos). Where none qualifies it takes the coarse pixel
// of nearest depth, so an edge never blurs across and no pixel stays dark. A fragment pass: on llvmpipe a
// memory-bound pass costs several times more as compute (gl/probe/machine_probe.h).
#pragma once

#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

class Frame;

class JointUpsample {
public:
    JointUpsample();
    // Writes fullIndirect from coarseIndirect, guided by both G-buffers' geometry targets (normal and eye
    // depth, glsl/common/gbuffer.glsl). `frame` draws the full-screen triangle.
    void run(const Frame& frame, const Texture& coarseGeometry, const Texture& coarseIndirect,
             const Texture& fullGeometry, const Texture& fullIndirect, PassTimers& timers);

    float depthTolerance = 0.05f;
    float normalTolerance = 0.1f;

private:
    Program program_;
    Framebuffer fbo_{"joint-upsample.fbo"};
};

} // namespace bounce::gl
