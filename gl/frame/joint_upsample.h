// Indirect light computed on a coarser frame, brought to the full frame by joint bilateral upsampling
// (the demo's frame budget: gl::Renderer::setIndirectScale). Each full-resolution pixel blends the four
// nearest coarse pixels with their bilinear weights, keeping only those on the same surface as itself by
// its own G-buffer: eye depth within `depthTolerance` of its own (relative) and normals within
// `normalTolerance` (1 - cos). Where none qualifies it takes the coarse pixel of nearest depth, so an
// edge never blurs across and no pixel stays dark. A fragment pass: on llvmpipe a memory-bound pass costs
// several times more as compute (gl/probe/machine_probe.h).
#pragma once

#include "gl/frame/frame.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

class JointUpsample {
public:
    JointUpsample();
    // Writes full.indirect() from coarse.indirect(), guided by both G-buffers (normal and eye depth).
    void run(Frame& coarse, Frame& full, PassTimers& timers);

    float depthTolerance = 0.05f;
    float normalTolerance = 0.1f;

private:
    Program program_;
    Framebuffer fbo_{"joint-upsample.fbo"};
};

} // namespace bounce::gl
