#include "gl/frame/points/pixel_gather.h"

#include <algorithm>

#include "gl/frame/bindings.h"
#include "gl/frame/points/bindings.h"
#include "gl/gl.h"
#include "gl/resource/dispatch.h"

namespace bounce::gl {

namespace {

// gather_select.comp past its first level test, per scope: a texel of level l tests l more levels (one
// outside every level all of them) and reads its patch state (8 bytes: gGeometry or mrNormal) and below
// the coarsest level its parent's (a bound: every patch continuous); each valid fragment adds an atomic
// and an 8-byte entry, and one above level 0 its ranges (24 bytes) and its eight neighbours' states and
// ranges (a bound: min(valid, the pyramid's patches) of them above level 0). The two images are cleared.
PassCost selectWork(const MultiresPyramid& pyramid, int valid)
{
    const int top = pyramid.coarsestLevel();
    PassCost w;
    double inLevels = 0.0, coarse = 0.0;
    for (int l = 0; l <= top; ++l) {
        const glm::ivec4 r = pyramid.levelRect(l);
        const double texels = double(r.z) * r.w;
        inLevels += texels;
        if (l > 0) coarse += texels;
        w.flopsFixed += texels * l * 6;
        w.fetchesFixed += texels * (l < top ? 2 : 1);
    }
    const glm::ivec2 f = pyramid.flattenedSize();
    const double flattened = double(f.x) * f.y, above = std::min(double(valid), coarse);
    w.flopsFixed += (flattened - inLevels) * top * 6 + above * 8 * 30;
    w.bytesFixed = w.fetchesFixed * 8 + valid * (8 + 8) + above * (24 + 8 * (2 * 8 + 24)) + flattened * 2 * 16 + 4 + 4;
    w.fetchesFixed += above * (3 + 8 * (2 + 3));
    return w;
}

} // namespace

PixelGather::PixelGather(Frame& frame, const MultiresSettings& settings)
    : pyramid_(frame.width(), frame.height(), settings),
      select_(Program::compute("points.gatherSelect", "frame/points/gather_select.comp"))
{
    allocate();
}

void PixelGather::allocate()
{
    const glm::ivec2 f = pyramid_.flattenedSize();
    // At most one target per texel of the flattened buffer (one valid fragment per pixel in the worst case).
    targets_ = Buffer("points.gatherTargets", kGatherListHeaderBytes + std::size_t(f.x) * f.y * 8);
    diffuse_ = Texture::create2D("points.illumination.diffuse", GL_RGBA32F, f.x, f.y);
    glossy_ = Texture::create2D("points.illumination.glossy", GL_RGBA32F, f.x, f.y);
}

int PixelGather::select(Frame& frame, PassTimers& timers)
{
    if (pyramid_.resize(frame.width(), frame.height())) allocate();
    pyramid_.build(frame, timers);
    // gather_select.comp per texel of the flattened buffer: the bounds test and level 0's; the rest is per
    // scope (selectWork), from the pyramid's layout and the valid fragments read back.
    PassCost cost;
    cost.flops = 8;
    auto t = timers.scope("gather-select", cost);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    diffuse_.clear(0, zero); // alpha 0: no valid fragment (what the upsampling reads)
    glossy_.clear(0, zero);
    clearGatherCount(targets_);
    frame.bindGBuffer();
    pyramid_.bind();
    pyramid_.setUniforms(select_);
    targets_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_GATHER_TARGETS);
    const glm::ivec2 f = pyramid_.flattenedSize();
    t.expectComputes(computeInvocations({f.x, f.y, 1}, {8, 8, 1}));
    select_.set("flattenedSize", f);
    dispatchCompute(select_, {f.x, f.y, 1}, {8, 8, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    std::uint32_t n = 0;
    targets_.download(0, sizeof(n), &n);
    count_ = int(n);
    t.addWork(selectWork(pyramid_, count_));
    return count_;
}

void PixelGather::bindForGather(Frame& frame, Program& program)
{
    frame.bindGBuffer();
    pyramid_.bind();
    pyramid_.setUniforms(program);
    targets_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_GATHER_TARGETS);
    diffuse_.bindImage(0, GL_WRITE_ONLY, 0, GL_RGBA32F);
    glossy_.bindImage(1, GL_WRITE_ONLY, 0, GL_RGBA32F);
    program.set("cameraPosition", frame.camera().position);
}

void PixelGather::upsample(Frame& frame, PassTimers& timers)
{
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    pyramid_.upsample(frame, diffuse_, timers, &glossy_);
}

void dispatchPerTarget(const Program& program, int count, int localSize)
{
    if (count > 0) dispatchRows(program, std::size_t(count), localSize);
}

double perTargetInvocations(int count, int localSize)
{
    return count > 0 ? rowsInvocations(std::size_t(count), localSize) : 0.0;
}

} // namespace bounce::gl
