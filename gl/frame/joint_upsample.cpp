#include "gl/frame/joint_upsample.h"

#include "gl/frame/bindings.h"
#include "gl/gl.h"
#include "gl/resource/pass_state.h"

namespace bounce::gl {

JointUpsample::JointUpsample()
    : program_(Program::graphics("joint-upsample", "frame/fullscreen.vert", "frame/joint_upsample.frag"))
{}

void JointUpsample::run(Frame& coarse, Frame& full, PassTimers& timers)
{
    PassCost cost; // joint_upsample.frag per pixel: its normal and depth, four coarse pixels' of both
    cost.flops = 80;
    cost.fetches = 1 + 4 * 2;
    cost.bytesRead = 8 + 4 * (8 + 16);
    cost.bytesWritten = 16;
    auto t = timers.scope("joint-upsample", cost);
    t.expectFragments(full.width(), full.height());
    fbo_.attach(GL_COLOR_ATTACHMENT0, full.indirect());
    PassState::fullscreen(fbo_, full.width(), full.height()).apply();
    coarse.indirect().bind(UNIT_UPSAMPLE_COARSE_INDIRECT);
    coarse.geometry().bind(UNIT_UPSAMPLE_COARSE_GEOMETRY);
    full.geometry().bind(UNIT_UPSAMPLE_FULL_GEOMETRY);
    program_.set("coarseSize", glm::ivec2(coarse.width(), coarse.height()));
    program_.set("scale",
                 glm::vec2(float(coarse.width()) / float(full.width()), float(coarse.height()) / float(full.height())));
    program_.set("depthTolerance", depthTolerance);
    program_.set("normalTolerance", normalTolerance);
    program_.use();
    full.drawFullscreen();
}

} // namespace bounce::gl
