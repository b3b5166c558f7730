#include "gl/technique/isr/vpl_sample.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/technique/isr/bindings.h"

namespace bounce::gl {

VplSampler::VplSampler() : program_(Program::compute("vpl.sample", "technique/isr/vpl_sample.comp"))
{}

int VplSampler::sideFor(int vpls, int views, int size)
{
    const int side = int(std::floor(std::sqrt(double(vpls) / double(std::max(views, 1))) + 1e-9));
    return std::clamp(side, 1, std::max(size, 1));
}

int VplSampler::sample(const RsmPass& rsm, Buffer& cache, int side, PassTimers& timers)
{
    PassCost cost; // vpl_sample.comp per VPL: four RSM texels of its texel's mip level, one 48-byte VPL
    cost.flops = 30;
    cost.fetches = 4;
    cost.bytesRead = 4 * 16;
    cost.bytesWritten = double(kVplBytes);
    auto t = timers.scope("vpl-sample", cost);
    const int count = side * side * rsm.viewCount();
    t.expectComputes(count <= 0 ? 0.0 : computeInvocations({count, 1, 1}, {64, 1, 1}));
    if (count <= 0) return 0;
    if (cache.bytes() < std::size_t(count) * kVplBytes) throw std::logic_error("VPL cache too small");
    rsm.bind();
    cache.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_ISR_VPL_CACHE);
    program_.set("rsmSize", rsm.size());
    program_.set("side", side);
    program_.set("viewCount", rsm.viewCount());
    program_.set("level", float(std::log2(double(rsm.size()) / double(side))));
    program_.use();
    glDispatchCompute(GLuint((count + 63) / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    return count;
}

} // namespace bounce::gl
