#include "gl/frame/points/adaptive_pixels.h"

#include <algorithm>
#include <cmath>

#include "gl/frame/bindings.h"
#include "gl/frame/points/bindings.h"
#include "gl/gl.h"
#include "gl/resource/dispatch.h"

namespace bounce::gl {

namespace {

constexpr int kCoarseGrid = 4; // §3.3: "starting with pixels on an initial 4 x 4 sampling grid"

// Pixels of a width x height image on the grid of spacing s (x % s == 0 and y % s == 0).
double gridPixels(int width, int height, int s)
{
    return double((width + s - 1) / s) * double((height + s - 1) / s);
}

// The pixels a level tests (adaptive.glsl): the first level's grid, else those on the spacing / 2 grid
// off the spacing grid.
double candidates(int width, int height, int firstGrid, int spacing)
{
    if (firstGrid > 0) return gridPixels(width, height, firstGrid);
    return gridPixels(width, height, spacing / 2) - gridPixels(width, height, spacing);
}

// adaptive_select.comp past its grid tests, per scope: each candidate reads its geometry texel and stores
// its state (a bound: every candidate on geometry); above the first level it also reads its four parents'
// geometry, diffuse colour and two light texels for the coherence metric; each target taken adds an
// atomic and an 8-byte entry. The first level clears the two light images and the states.
PassCost selectWork(double pixels, double tested, bool firstLevel, double taken)
{
    PassCost w;
    w.flopsFixed = tested * (firstLevel ? 2 : 370);
    w.fetchesFixed = tested * (firstLevel ? 1 : 1 + 4 * 4);
    w.bytesFixed = tested * ((firstLevel ? 8 : 8 + 4 * (8 + 8 + 16 + 16)) + 1) + taken * (8 + 8) + 4 + 4;
    if (firstLevel) w.bytesFixed += pixels * (16 + 16 + 1);
    return w;
}

// adaptive_mean.comp, run inside "adaptive-select" on level 1, per scope: per pixel its diffuse-light
// texel and the group sum; per gathered pixel its glossy-light and direct texels, diffuse colour,
// luminance and logarithm; one partial per 16 x 16 tile, summed by one group, and 16 bytes read back.
PassCost meanWork(int width, int height, double gathered)
{
    const double pixels = double(width) * height, tiles = double((width + 15) / 16) * double((height + 15) / 16);
    PassCost w;
    w.flopsFixed = pixels * 2 + gathered * 20 + tiles * 2;
    w.fetchesFixed = pixels + gathered * 3 + tiles;
    w.bytesFixed = pixels * 16 + gathered * (16 + 16 + 8) + tiles * 2 * 16 + 16 + 16;
    return w;
}

// adaptive_interpolate.comp past its grid tests, per scope: each candidate reads its state; each pixel
// interpolated (a bound: every candidate not taken) reads its geometry, and per parent of nonzero
// bilinear weight (8/3 on average: two on an edge of the cell, four at its centre) its geometry and two
// light texels, and writes its two light texels.
PassCost interpolateWork(double tested, double interpolated)
{
    PassCost w;
    w.flopsFixed = interpolated * (70 + 8.0 / 3.0 * 80);
    w.fetchesFixed = tested + interpolated * (1 + 8.0 / 3.0 * 3);
    w.bytesFixed = tested + interpolated * (8 + 8.0 / 3.0 * (8 + 2 * 16) + 2 * 16);
    return w;
}

} // namespace

AdaptivePixels::AdaptivePixels(Frame& frame, const AdaptiveSettings& settings)
    : settings_(settings),
      select_(Program::compute("points.adaptiveSelect", "frame/points/adaptive_select.comp")),
      interpolate_(Program::compute("points.adaptiveInterpolate", "frame/points/adaptive_interpolate.comp")),
      compose_(Program::compute("points.adaptiveCompose", "frame/points/adaptive_compose.comp")),
      mean_(Program::compute("points.adaptiveMean", "frame/points/adaptive_mean.comp")),
      meanFinal_(Program::compute("points.adaptiveMeanFinal", "frame/points/adaptive_mean.comp", {{"MEAN_FINAL", "1"}}))
{
    allocate(frame.width(), frame.height());
}

void AdaptivePixels::allocate(int width, int height)
{
    width_ = width;
    height_ = height;
    state_ = Texture::create2D("points.adaptive.state", GL_R8UI, width, height);
    diffuse_ = Texture::create2D("points.adaptive.diffuse", GL_RGBA32F, width, height);
    glossy_ = Texture::create2D("points.adaptive.glossy", GL_RGBA32F, width, height);
    accumulated_ = Texture::create2D("points.adaptive.accumulated", GL_RGBA32F, width, height);
    targets_ = Buffer("points.adaptiveTargets", kGatherListHeaderBytes + std::size_t(width) * height * 8);
    partials_ = Texture::create2D("points.adaptive.meanPartials", GL_RGBA32F, (width + 15) / 16, (height + 15) / 16);
}

void AdaptivePixels::setCommon(Frame& frame, Program& program, int spacing)
{
    const core::Bounds& b = frame.gpuScene().bounds();
    program.set("viewSize", glm::ivec2(width_, height_));
    program.set("spacing", spacing);
    program.set("sceneDiagonal", std::max(glm::length(b.extent()), 1e-6f));
}

int AdaptivePixels::select(Frame& frame, int level, PassTimers& timers)
{
    if (frame.width() != width_ || frame.height() != height_) allocate(frame.width(), frame.height());
    // Level l >= 1 refines the grid of spacing 4 / 2^(l - 1): its candidates lie on the grid half as wide.
    const int spacing = level == 0 ? 0 : kCoarseGrid >> (level - 1);
    const int firstGrid = level == 0 ? (settings_.adaptive ? kCoarseGrid : 1) : 0;
    // adaptive_select.comp (and on level 1 adaptive_mean.comp) per invocation: the bounds and grid tests;
    // the rest is per scope (selectWork, meanWork), from the grids and the targets read back.
    PassCost cost;
    cost.flops = 6;
    auto t = timers.scope("adaptive-select", cost);
    t.expectComputes(computeInvocations({width_, height_, 1}, {8, 8, 1}));
    if (level == 1) // logAverageLuminance's two dispatches
        t.expectComputes(computeInvocations({width_, height_, 1}, {16, 16, 1}) + 16.0 * 16.0);
    if (level == 0) {
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        diffuse_.clear(0, zero);
        glossy_.clear(0, zero);
        const GLuint undecided = 0;
        glClearTexImage(state_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &undecided);
    }
    clearGatherCount(targets_);
    frame.bindGBuffer();
    setCommon(frame, select_, spacing);
    select_.set("firstGrid", firstGrid);
    select_.set("epsilon", settings_.epsilon * float(1 << std::max(level - 1, 0)));
    select_.set("lambda", settings_.lambda);
    if (level == 1) {
        logAverage_ = logAverageLuminance(frame);
        t.addWork(meanWork(width_, height_, sampled_)); // sampled_: the first level's targets
    }
    select_.set("logAverage", logAverage_);
    state_.bindImage(0, GL_READ_WRITE, 0, GL_R8UI);
    diffuse_.bindImage(1, GL_READ_ONLY, 0, GL_RGBA32F);
    glossy_.bindImage(2, GL_READ_ONLY, 0, GL_RGBA32F);
    targets_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_GATHER_TARGETS);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    dispatchCompute(select_, {width_, height_, 1}, {8, 8, 1});
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    std::uint32_t n = 0;
    targets_.download(0, sizeof(n), &n);
    selected_ = int(n);
    sampled_ = level == 0 ? int(n) : sampled_ + int(n);
    t.addWork(selectWork(double(width_) * height_, candidates(width_, height_, firstGrid, spacing), level == 0, n));
    return int(n);
}

float AdaptivePixels::logAverageLuminance(Frame& frame)
{
    // The first level's samples: a quarter-by-quarter grid (what the paper's display-scaled L_o gets from
    // its tone mapping), summed per 16 x 16 tile, then the tiles by one work group.
    frame.bindGBuffer();
    mean_.set("viewSize", glm::ivec2(width_, height_));
    diffuse_.bindImage(0, GL_READ_ONLY, 0, GL_RGBA32F);
    glossy_.bindImage(1, GL_READ_ONLY, 0, GL_RGBA32F);
    partials_.bindImage(2, GL_WRITE_ONLY, 0, GL_RGBA32F);
    frame.direct().bindImage(3, GL_READ_ONLY, 0, GL_RGBA32F);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    dispatchCompute(mean_, {width_, height_, 1}, {16, 16, 1});
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    partials_.bindImage(0, GL_READ_WRITE, 0, GL_RGBA32F);
    dispatchCompute(meanFinal_, {16, 16, 1}, {16, 16, 1});
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    float texel[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glGetTextureSubImage(partials_.id(), 0, 0, 0, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof texel, texel);
    return texel[2];
}

float AdaptivePixels::logAverageLuminanceOnCpu(Frame& frame) const
{
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    const std::vector<float> d = diffuse_.readFloats(0, 4), g = glossy_.readFloats(0, 4),
                             c = frame.diffuse().readFloats(0, 4), e = frame.direct().readFloats(0, 4);
    constexpr double kLogDelta = 1e-4; // adaptive.glsl's
    const double w[3] = {0.2126, 0.7152, 0.0722};
    double sum = 0.0;
    int n = 0;
    for (std::size_t i = 0; i + 3 < d.size(); i += 4) {
        if (d[i + 3] < 1.0f) continue; // not gathered
        double l = 0.0;
        for (int k = 0; k < 3; ++k) l += w[k] * (double(c[i + k]) * d[i + k] + g[i + k] + e[i + k]);
        sum += std::log(kLogDelta + l);
        ++n;
    }
    return n > 0 ? float(std::exp(sum / n)) : 0.0f;
}

void AdaptivePixels::bindForGather(Frame& frame, Program& program)
{
    frame.bindGBuffer();
    // gather_target.glsl reads level-0 targets through multires.glsl's layout: the image alone.
    program.set("levelOrigin[0]", glm::ivec2(0));
    program.set("levelSize[0]", glm::ivec2(width_, height_));
    program.set("coarsestLevel", 0);
    program.set("cameraPosition", frame.camera().position);
    targets_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_GATHER_TARGETS);
    diffuse_.bindImage(0, GL_WRITE_ONLY, 0, GL_RGBA32F);
    glossy_.bindImage(1, GL_WRITE_ONLY, 0, GL_RGBA32F);
}

void AdaptivePixels::interpolate(Frame& frame, int level, PassTimers& timers)
{
    // adaptive_interpolate.comp per pixel: the bounds and grid tests; the candidates' work per scope below.
    PassCost cost;
    cost.flops = 6;
    auto t = timers.scope("interpolate", cost);
    t.expectComputes(level == 0 ? 0.0 : computeInvocations({width_, height_, 1}, {8, 8, 1}));
    if (level == 0) return;
    const int spacing = kCoarseGrid >> (level - 1);
    const double tested = candidates(width_, height_, 0, spacing);
    t.addWork(interpolateWork(tested, std::max(tested - selected_, 0.0)));
    frame.bindGBuffer();
    setCommon(frame, interpolate_, spacing);
    state_.bindImage(0, GL_READ_ONLY, 0, GL_R8UI);
    diffuse_.bindImage(1, GL_READ_WRITE, 0, GL_RGBA32F);
    glossy_.bindImage(2, GL_READ_WRITE, 0, GL_RGBA32F);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    dispatchCompute(interpolate_, {width_, height_, 1}, {8, 8, 1});
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

int AdaptivePixels::postFilterRadius() const
{
    if (settings_.postFilter >= 0) return settings_.postFilter;
    return (settings_.glossyScene ? 1 : 3) * std::min(width_, height_) / 512;
}

void AdaptivePixels::compose(Frame& frame, float newWeight, PassTimers& timers)
{
    // adaptive_compose.comp per pixel: its geometry texel, and on geometry (a bound: every pixel) its diffuse
    // colour and two light texels, the product and sum; with the post-filter, per pixel of the window its
    // geometry texel, the geometric term, the weight's exp and two light texels; in progressive mode the
    // running mean's texel and mix; two RGBA32F stores.
    const bool progressive = newWeight < 1.0f;
    const int r = postFilterRadius();
    const double window = r > 0 ? double((2 * r + 1) * (2 * r + 1)) : 0.0;
    PassCost cost;
    cost.flops = 8 + (progressive ? 9 : 0) + window * (45 + 20 + 14);
    cost.fetches = 4 + (progressive ? 1 : 0) + window * 3;
    cost.bytesRead = 8 + 8 + 2 * 16 + (progressive ? 16 : 0) + window * (8 + 2 * 16);
    cost.bytesWritten = 2 * 16;
    auto t = timers.scope("compose", cost);
    t.expectComputes(computeInvocations({width_, height_, 1}, {8, 8, 1}));
    frame.bindGBuffer();
    setCommon(frame, compose_, 1);
    compose_.set("newWeight", newWeight);
    compose_.set("postFilter", r);
    diffuse_.bindImage(0, GL_READ_ONLY, 0, GL_RGBA32F);
    glossy_.bindImage(1, GL_READ_ONLY, 0, GL_RGBA32F);
    accumulated_.bindImage(2, GL_READ_WRITE, 0, GL_RGBA32F);
    frame.indirect().bindImage(3, GL_WRITE_ONLY, 0, GL_RGBA32F);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    dispatchCompute(compose_, {width_, height_, 1}, {8, 8, 1});
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

} // namespace bounce::gl
