#include "gl/frame/joint_upsample.h"

#include "gl/frame/bindings.h"
#include "gl/frame/frame.h"
#include "gl/gl.h"
#include "gl/resource/pass_state.h"

namespace bounce::gl {

JointUpsample::JointUpsample()
    : program_(Program::graphics("joint-upsample", "frame/fullscreen.vert", "frame/joint_upsample.frag"))
{}

void JointUpsample::run(const Frame& frame, const Texture& coarseGeometry, const Texture& coarseIndirect,
                        const Texture& fullGeometry, const Texture& fullIndirect, PassTimers& timers)
{
    PassCost cost; // joint_upsample.frag per pixel: its normal and depth, four coarse pixels' of both
    cost.flops = 80;
    cost.fetches = 1 + 4 * 2;
    cost.bytesRead = 8 + 4 * (8 + 16);
    cost.bytesWritten = 16;
    const int w = fullIndirect.width(), h = fullIndirect.height();
    auto t = timers.scope("joint-upsample", cost);
    t.expectFragments(w, h);
    fbo_.attach(GL_COLOR_ATTACHMENT0, fullIndirect);
    PassState::fullscreen(fbo_, w, h).apply();
    coarseIndirect.bind(UNIT_UPSAMPLE_COARSE_INDIRECT);
    coarseGeometry.bind(UNIT_UPSAMPLE_COARSE_GEOMETRY);
    fullGeometry.bind(UNIT_UPSAMPLE_FULL_GEOMETRY);
    program_.set("coarseSize", glm::ivec2(coarseIndirect.width(), coarseIndirect.height()));
    program_.set("scale",
                 glm::vec2(float(coarseIndirect.width()) / float(w), float(coarseIndirect.height()) / float(h)));
    program_.set("depthTolerance", depthTolerance);
    program_.set("normalTolerance", normalTolerance);
    program_.use();
    frame.drawFullscreen();
}

} // namespace bounce::gl
