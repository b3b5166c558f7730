#include "gl/frame/multires.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "gl/context/context.h"
#include "gl/frame/bindings.h"
#include "gl/gl.h"
#include "gl/probe/machine_probe.h"
#include "gl/resource/dispatch.h"
#include "gl/resource/pass_state.h"

namespace bounce::gl {

namespace {

int ceilDiv(int a, int b)
{
    return (a + b - 1) / b;
}

// Smallest l with 2^l >= n: the level whose single patch covers n pixels.
int ceilLog2(int n)
{
    int l = 0;
    while ((1 << l) < n) ++l;
    return l;
}

} // namespace

std::vector<ParamDecl> multiresParams()
{
    const MultiresSettings d;
    // The thresholds are uniforms of the passes that test patches: changing them recompiles nothing.
    std::vector<ParamDecl> p{
        {"depthThreshold", ParamType::Float, d.depthThreshold, 0, 100,
         "eye-space discontinuity: a patch is subdivided when (max - min) eye depth >= this x min depth; 0: full "
         "resolution",
         false, ParamUpdate::Uniform},
        {"normalThreshold", ParamType::Float, d.normalThreshold, 0, 4,
         "eye-space discontinuity: a patch is subdivided when any normal component spans >= this; 0: full resolution",
         false, ParamUpdate::Uniform},
        {"coarsestLevel", ParamType::Int, kAutoValue, 0, MultiresPyramid::kMaxLevels - 1,
         "coarsest multiresolution patch: 2^level pixels per side; auto: the paper's 64x64 coarsest buffer (8x8 pixels "
         "at 512^2)"},
    };
    p.back().allowAuto = true;
    return p;
}

MultiresSettings multiresSettingsFrom(const ParamValues& v)
{
    MultiresSettings s;
    s.depthThreshold = float(v.get("depthThreshold"));
    s.normalThreshold = float(v.get("normalThreshold"));
    s.coarsestLevel = v.isAuto("coarsestLevel") ? MultiresSettings::kAutoLevel : v.getInt("coarsestLevel");
    return s;
}

std::vector<glm::ivec4> multiresLevelRects(int width, int height, int coarsestLevel)
{
    if (width < 1 || height < 1) throw std::invalid_argument("multiresolution buffer of an empty image");
    const int levels =
        std::clamp(std::min(coarsestLevel, ceilLog2(std::max(width, height))), 0, MultiresPyramid::kMaxLevels - 1);
    std::vector<glm::ivec4> rects{{0, 0, width, height}};
    int y = 0;
    for (int l = 1; l <= levels; ++l) {
        const glm::ivec4 r(width, y, ceilDiv(width, 1 << l), ceilDiv(height, 1 << l));
        rects.push_back(r);
        y += r.w;
    }
    return rects;
}

int autoCoarsestLevel(int width, int height)
{
    const int side = std::max(width, height);
    int l = 0;
    while (l + 1 < MultiresPyramid::kMaxLevels && ceilDiv(side, 1 << (l + 1)) >= 64) ++l;
    return l;
}

MultiresPyramid::MultiresPyramid(int width, int height, const MultiresSettings& settings)
    : settings_(settings),
      upsampleFbo_("multires.upsample.fbo"),
      reduceFromGBuffer_(
          Program::compute("multires.minmax.level1", "frame/multires_minmax.comp", {{"FROM_GBUFFER", "1"}})),
      reduce_(Program::compute("multires.minmax", "frame/multires_minmax.comp")),
      upsampleAsFragments_(preferFragmentPasses()),
      upsample_(upsampleProgram(upsampleAsFragments_, false))
{
    if (settings_.coarsestLevel < MultiresSettings::kAutoLevel)
        throw std::invalid_argument("coarsestLevel must be at least 0, or -1 for the paper's 64 x 64 coarsest buffer");
    resize(width, height);
}

bool MultiresPyramid::resize(int width, int height)
{
    if (width == width_ && height == height_ && position_) return false;
    width_ = width;
    height_ = height;
    const int coarsest = settings_.coarsestLevel == MultiresSettings::kAutoLevel ? autoCoarsestLevel(width, height)
                                                                                 : settings_.coarsestLevel;
    rects_ = multiresLevelRects(width, height, coarsest);
    levels_ = int(rects_.size()) - 1;
    int pyrW = 1, pyrH = 1;
    flattened_ = glm::ivec2(width, height);
    if (levels_ > 0) {
        pyrW = rects_[1].z;
        pyrH = rects_.back().y + rects_.back().w;
        flattened_ = glm::ivec2(width + pyrW, std::max(height, pyrH));
    }
    // Levels 1..coarsest of the min-max pyramid (level 0 is the G-buffer), one column.
    position_ = Texture::create2D("multires.pyramid.position", GL_RGBA32F, pyrW, pyrH);
    normal_ = Texture::create2D("multires.pyramid.normal", GL_RGBA16F, pyrW, pyrH);
    diffuse_ = Texture::create2D("multires.pyramid.diffuse", GL_RGBA16F, pyrW, pyrH);
    depth_ = Texture::create2D("multires.pyramid.depthRange", GL_RG32F, pyrW, pyrH);
    normalMin_ = Texture::create2D("multires.pyramid.normalMin", GL_RGBA16F, pyrW, pyrH);
    normalMax_ = Texture::create2D("multires.pyramid.normalMax", GL_RGBA16F, pyrW, pyrH);
    return true;
}

void MultiresPyramid::setUniforms(Program& program) const
{
    for (int l = 0; l <= levels_; ++l) {
        const std::string i = "[" + std::to_string(l) + "]";
        program.set("levelOrigin" + i, glm::ivec2(rects_[l].x, rects_[l].y));
        program.set("levelSize" + i, glm::ivec2(rects_[l].z, rects_[l].w));
    }
    program.set("coarsestLevel", levels_);
    program.set("depthThreshold", settings_.depthThreshold);
    program.set("normalThreshold", settings_.normalThreshold);
}

void MultiresPyramid::bind() const
{
    position_.bind(UNIT_MULTIRES_FIRST + 0);
    normal_.bind(UNIT_MULTIRES_FIRST + 1);
    diffuse_.bind(UNIT_MULTIRES_FIRST + 2);
    depth_.bind(UNIT_MULTIRES_FIRST + 3);
    normalMin_.bind(UNIT_MULTIRES_FIRST + 4);
    normalMax_.bind(UNIT_MULTIRES_FIRST + 5);
}

void MultiresPyramid::build(Frame& frame, PassTimers& timers)
{
    resize(frame.width(), frame.height());
    // multires_minmax.comp per patch: four children (two G-buffer texels at level 1, six pyramid texels
    // above; about four on average), six image stores.
    PassCost cost;
    cost.flops = 70;
    cost.fetches = 4 * 4;
    cost.bytesRead = 4 * 44;
    cost.bytesWritten = 16 + 4 * 8 + 8;
    auto t = timers.scope("minmax-mipmap", cost);
    t.expectComputes(0.0);
    if (levels_ == 0) return; // a 1x1 image, or coarsestLevel 0: the pixels are the only level
    frame.bindGBuffer();
    bind();
    position_.bindImage(0, GL_WRITE_ONLY);
    normal_.bindImage(1, GL_WRITE_ONLY);
    diffuse_.bindImage(2, GL_WRITE_ONLY);
    depth_.bindImage(3, GL_WRITE_ONLY);
    normalMin_.bindImage(4, GL_WRITE_ONLY);
    normalMax_.bindImage(5, GL_WRITE_ONLY);
    setUniforms(reduceFromGBuffer_);
    setUniforms(reduce_);
    for (int l = 1; l <= levels_; ++l) {
        Program& program = l == 1 ? reduceFromGBuffer_ : reduce_;
        program.set("level", l);
        program.use();
        t.expectComputes(computeInvocations({rects_[l].z, rects_[l].w, 1}, {8, 8, 1}));
        glDispatchCompute(GLuint(ceilDiv(rects_[l].z, 8)), GLuint(ceilDiv(rects_[l].w, 8)), 1);
        // Level l is read (texelFetch) by the next level and by every pass of the technique after it.
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
}

void MultiresPyramid::upsample(Frame& frame, const Texture& illumination, PassTimers& timers,
                               const Texture* unmodulated)
{
    // multires_upsample.glsl per pixel: its geometry flag, the levels up to its fragment's, four
    // neighbours and the diffuse colour; one RGBA32F target or image.
    PassCost cost;
    cost.flops = 40;
    cost.fetches = 2 + 2 + 4;
    cost.bytesRead = 8 + 2 * 16 + 4 * 16 + 8;
    cost.bytesWritten = 16;
    auto t = timers.scope("upsample", cost);
    if (upsampleAsFragments_)
        t.expectFragments(width_, height_);
    else
        t.expectComputes(computeInvocations({width_, height_, 1}, {8, 8, 1}));
    frame.bindGBuffer();
    bind();
    illumination.bind(UNIT_MULTIRES_ILLUMINATION);
    if (unmodulated && !upsampleUnmodulated_) upsampleUnmodulated_ = upsampleProgram(upsampleAsFragments_, true);
    Program& program = unmodulated ? upsampleUnmodulated_ : upsample_;
    if (unmodulated) unmodulated->bind(UNIT_MULTIRES_UNMODULATED);
    setUniforms(program);
    program.use();
    // The technique rendered (or stored, from compute passes) into the illumination buffers.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    if (upsampleAsFragments_) {
        upsampleFbo_.attach(GL_COLOR_ATTACHMENT0, frame.indirect());
        PassState::fullscreen(upsampleFbo_, width_, height_).apply();
        frame.drawFullscreen();
        return;
    }
    frame.indirect().bindImage(0, GL_WRITE_ONLY, 0, GL_RGBA32F);
    glDispatchCompute(GLuint(ceilDiv(width_, 8)), GLuint(ceilDiv(height_, 8)), 1);
    // The composite (and any read-back) samples the indirect texture.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

Program MultiresPyramid::upsampleProgram(bool asFragments, bool unmodulated)
{
    std::vector<Define> d;
    if (unmodulated) d.push_back({"UNMODULATED", "1"});
    const std::string label = unmodulated ? "multires.upsample.unmodulated" : "multires.upsample";
    return asFragments ? Program::graphics(label, "frame/fullscreen.vert", "frame/multires_upsample.frag", d)
                       : Program::compute(label, "frame/multires_upsample.comp", d);
}

} // namespace bounce::gl
