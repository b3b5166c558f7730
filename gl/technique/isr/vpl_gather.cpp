#include "gl/technique/isr/vpl_gather.h"

#include <algorithm>
#include <stdexcept>

#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/technique/isr/bindings.h"
#include "gl/technique/isr/vpl_sample.h"

namespace bounce::gl {

namespace {}

int vplsPerBlock()
{
    static const int perBlock = [] {
        GLint maxBytes = 0;
        glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &maxBytes);
        int n = 1024;
        while (n > 1 && std::size_t(n) * VplSampler::kVplBytes > std::size_t(std::max(maxBytes, 0))) n /= 2;
        return n;
    }();
    return perBlock;
}

std::vector<Define> vplBlockDefines()
{
    return {{"VPL_BLOCK_SIZE", std::to_string(vplsPerBlock())}};
}

int vplBlockCount(int count)
{
    return count <= 0 ? 0 : (count + vplsPerBlock() - 1) / vplsPerBlock();
}

std::size_t vplCacheBytes(int vpls)
{
    return std::size_t(std::max(vplBlockCount(vpls), 1)) * std::size_t(vplsPerBlock()) * VplSampler::kVplBytes;
}

void reserveVplCache(Buffer& cache, int vpls)
{
    const std::size_t needed = vplCacheBytes(vpls);
    if (!cache || cache.bytes() < needed) cache = Buffer("vpl.cache", needed);
}

int bindVplBlock(const Buffer& cache, int block, int count)
{
    const std::size_t blockBytes = std::size_t(vplsPerBlock()) * VplSampler::kVplBytes;
    const std::size_t offset = std::size_t(block) * blockBytes;
    if (block < 0 || cache.bytes() < offset + blockBytes)
        throw std::logic_error("VPL cache of " + std::to_string(cache.bytes()) + " bytes has no block " +
                               std::to_string(block) + " (allocate it with vplCacheBytes)");
    glBindBufferRange(GL_UNIFORM_BUFFER, UBO_ISR_VPL_BLOCK, cache.id(), GLintptr(offset), GLsizeiptr(blockBytes));
    return std::clamp(count - block * vplsPerBlock(), 0, vplsPerBlock());
}

VplGather::VplGather() : program_(Program::compute("vpl.gather", "technique/isr/vpl_gather.comp", vplBlockDefines()))
{}

void VplGather::gather(Frame& frame, const Buffer& vpls, int count, PassTimers& timers, const std::string& pass)
{
    // vpl_gather.comp per pixel: three G-buffer texels, every VPL of every block, one image load (after
    // the first block) and store per block.
    const int blocks = vplBlockCount(count);
    PassCost cost;
    cost.flops = double(count) * kFlopsPerVpl / std::max(blocks, 1); // invocations are counted per dispatch
    cost.uniformWords = double(count) * kUniformWordsPerVpl / std::max(blocks, 1);
    cost.fetches = 3;
    cost.bytesRead = 3 * 16 + (blocks > 1 ? 16 : 0);
    cost.bytesWritten = 16;
    auto t = timers.scope(pass, cost);
    // One dispatch over the pixels per block of VPLs.
    t.expectComputes(count <= 0 ? 0.0 : blocks * computeInvocations({frame.width(), frame.height(), 1}, {8, 8, 1}));
    if (count <= 0) return; // the frame's indirect texture stays cleared
    frame.bindGBuffer();
    frame.indirect().bindImage(0, GL_READ_WRITE, 0, GL_RGBA32F);
    program_.set("outputSize", glm::ivec2(frame.width(), frame.height()));
    program_.use();
    // VPLs written by compute passes (as an SSBO) are read here through a uniform block.
    glMemoryBarrier(GL_UNIFORM_BARRIER_BIT);
    const GLuint gx = GLuint((frame.width() + 7) / 8), gy = GLuint((frame.height() + 7) / 8);
    for (int block = 0; block < vplBlockCount(count); ++block) {
        program_.set("vplCount", bindVplBlock(vpls, block, count));
        program_.set("accumulate", block > 0 ? 1 : 0);
        if (block > 0) glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glDispatchCompute(gx, gy, 1);
    }
    // The composite (and any read-back) samples the indirect texture.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

} // namespace bounce::gl
