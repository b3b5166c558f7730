#include "gl/technique/isr/vpl_gather.h"

#include <algorithm>

#include "gl/gl.h"

namespace bounce::gl {

VplGather::VplGather() : program_(Program::compute("vpl.gather", "technique/isr/vpl_gather.comp")) {}

void VplGather::gather(Frame& frame, const Buffer& vpls, int count, PassTimers& timers, const std::string& pass)
{
    auto t = timers.scope(pass);
    if (count <= 0) return; // the frame's indirect texture stays cleared
    frame.bindGBuffer();
    vpls.bindBase(GL_SHADER_STORAGE_BUFFER, 8);
    frame.indirect().bindImage(0, GL_READ_WRITE, 0, GL_RGBA32F);
    program_.set("outputSize", glm::ivec2(frame.width(), frame.height()));
    program_.use();
    // VPL writes (compute) must be visible to this pass's SSBO reads.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    const GLuint gx = GLuint((frame.width() + 7) / 8), gy = GLuint((frame.height() + 7) / 8);
    for (int begin = 0; begin < count; begin += kVplsPerDispatch) {
        program_.set("vplBegin", begin);
        program_.set("vplEnd", std::min(count, begin + kVplsPerDispatch));
        program_.set("accumulate", begin > 0 ? 1 : 0);
        if (begin > 0) glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glDispatchCompute(gx, gy, 1);
    }
    // The composite (and any read-back) samples the indirect texture.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

} // namespace bounce::gl
