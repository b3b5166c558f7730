#include "gl/technique/isr/multires_gather.h"

#include <algorithm>
#include <limits>
#include <string>
#include <stdexcept>

#include "gl/context/context.h"
#include "gl/gl.h"
#include "gl/technique/isr/vpl_gather.h"

namespace bounce::gl {

namespace {

int ceilDiv(int a, int b) { return (a + b - 1) / b; }

// Smallest l with 2^l >= n: the level whose single patch covers n pixels.
int ceilLog2(int n)
{
    int l = 0;
    while ((1 << l) < n) ++l;
    return l;
}

} // namespace

std::vector<glm::ivec4> multiresLevelRects(int width, int height, int coarsestLevel)
{
    if (width < 1 || height < 1) throw std::invalid_argument("multiresolution buffer of an empty image");
    const int levels = std::clamp(std::min(coarsestLevel, ceilLog2(std::max(width, height))), 0,
                                  MultiresGather::kMaxLevels - 1);
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
    while (l + 1 < MultiresGather::kMaxLevels && ceilDiv(side, 1 << (l + 1)) >= 64) ++l;
    return l;
}

MultiresGather::MultiresGather(Frame& frame, const MultiresSettings& settings)
    : settings_(settings), fbo_("multires.fbo"),
      counts_("multires.fragmentCounts", sizeof(unsigned) * kMaxLevels),
      reduce_(Program::compute("multires.minmax", "technique/isr/multires_minmax.comp")),
      stencilSetup_(Program::graphics("multires.stencil", "frame/fullscreen.vert", "technique/isr/multires_stencil.frag")),
      cacheGather_(gatherProgram("multires.gather", "technique/isr/multires_gather.frag", vplBlockDefines())),
      upsample_(Program::compute("multires.upsample", "technique/isr/multires_upsample.comp"))
{
    if (settings_.coarsestLevel < MultiresSettings::kAutoLevel)
        throw std::invalid_argument("coarsestLevel must be at least 0, or -1 for the paper's 64 x 64 coarsest buffer");
    allocate(frame.width(), frame.height());
}

Program MultiresGather::gatherProgram(const std::string& label, const std::string& fragmentPath,
                                      const std::vector<Define>& defines)
{
    return Program::graphics(label, "frame/fullscreen.vert", fragmentPath, defines);
}

void MultiresGather::allocate(int width, int height)
{
    width_ = width;
    height_ = height;
    const int coarsest = settings_.coarsestLevel == MultiresSettings::kAutoLevel ? autoCoarsestLevel(width, height)
                                                                                 : settings_.coarsestLevel;
    rects_ = multiresLevelRects(width, height, coarsest);
    levels_ = int(rects_.size()) - 1;
    int atlasW = width, atlasH = height, pyrW = 1, pyrH = 1;
    if (levels_ > 0) {
        pyrW = rects_[1].z;
        pyrH = rects_.back().y + rects_.back().w;
        atlasW = width + pyrW;
        atlasH = std::max(height, pyrH);
    }
    // Levels 1..coarsest of the min-max pyramid (level 0 is the G-buffer), one column.
    pyrPosition_ = Texture::create2D("multires.pyramid.position", GL_RGBA32F, pyrW, pyrH);
    pyrNormal_ = Texture::create2D("multires.pyramid.normal", GL_RGBA16F, pyrW, pyrH);
    pyrDiffuse_ = Texture::create2D("multires.pyramid.diffuse", GL_RGBA16F, pyrW, pyrH);
    pyrDepth_ = Texture::create2D("multires.pyramid.depthRange", GL_RG32F, pyrW, pyrH);
    pyrNormalMin_ = Texture::create2D("multires.pyramid.normalMin", GL_RGBA16F, pyrW, pyrH);
    pyrNormalMax_ = Texture::create2D("multires.pyramid.normalMax", GL_RGBA16F, pyrW, pyrH);
    // The flattened multiresolution illumination buffer and its stencil (§3.2.1).
    illumination_ = Texture::create2D("multires.illumination", GL_RGBA32F, atlasW, atlasH);
    stencil_ = Texture::create2D("multires.stencil", GL_DEPTH24_STENCIL8, atlasW, atlasH);
    fbo_.attach(GL_COLOR_ATTACHMENT0, illumination_);
    fbo_.attach(GL_DEPTH_STENCIL_ATTACHMENT, stencil_);
    fbo_.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    fbo_.checkComplete();
}

void MultiresGather::setCommonUniforms(Program& program) const
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

void MultiresGather::bindPyramid() const
{
    pyrPosition_.bind(kPyramidUnitBase + 0);
    pyrNormal_.bind(kPyramidUnitBase + 1);
    pyrDiffuse_.bind(kPyramidUnitBase + 2);
    pyrDepth_.bind(kPyramidUnitBase + 3);
    pyrNormalMin_.bind(kPyramidUnitBase + 4);
    pyrNormalMax_.bind(kPyramidUnitBase + 5);
}

void MultiresGather::buildPyramid(Frame& frame, PassTimers& timers)
{
    if (frame.width() != width_ || frame.height() != height_) allocate(frame.width(), frame.height());
    auto t = timers.scope("minmax-mipmap");
    if (levels_ == 0) return; // a 1x1 image, or coarsestLevel 0: the pixels are the only level
    frame.bindGBuffer();
    bindPyramid();
    pyrPosition_.bindImage(0, GL_WRITE_ONLY);
    pyrNormal_.bindImage(1, GL_WRITE_ONLY);
    pyrDiffuse_.bindImage(2, GL_WRITE_ONLY);
    pyrDepth_.bindImage(3, GL_WRITE_ONLY);
    pyrNormalMin_.bindImage(4, GL_WRITE_ONLY);
    pyrNormalMax_.bindImage(5, GL_WRITE_ONLY);
    setCommonUniforms(reduce_);
    reduce_.use();
    for (int l = 1; l <= levels_; ++l) {
        reduce_.set("level", l);
        glDispatchCompute(GLuint(ceilDiv(rects_[l].z, 8)), GLuint(ceilDiv(rects_[l].w, 8)), 1);
        // Level l is read (texelFetch) by the next level, the stencil pass and the gather.
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
}

void MultiresGather::markValidFragments(Frame& frame, PassTimers& timers)
{
    auto t = timers.scope("stencil-setup");
    counts_.clearToZero();
    const float zero[4] = {0, 0, 0, 0};
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE); // clears obey the write masks
    glStencilMask(0xFF);
    glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfi(fbo_.id(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
    fbo_.bind();
    glViewport(0, 0, illumination_.width(), illumination_.height());
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xFF);
    glStencilFunc(GL_ALWAYS, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE); // the fragments that survive the shader set the stencil to 1
    frame.bindGBuffer();
    bindPyramid();
    counts_.bindBase(GL_SHADER_STORAGE_BUFFER, kCountsBinding);
    setCommonUniforms(stencilSetup_);
    stencilSetup_.use();
    frame.drawFullscreen();
    glDisable(GL_STENCIL_TEST);
}

void MultiresGather::gather(Frame& frame, Program& program, PassTimers& timers, int draws,
                            const std::function<void(Program&, int)>& setupDraw)
{
    auto t = timers.scope("gather");
    fbo_.bind();
    glViewport(0, 0, illumination_.width(), illumination_.height());
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0x00);
    glStencilFunc(GL_EQUAL, 1, 0xFF); // only the valid multiresolution fragments (§3.2.1)
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE); // alpha keeps the stencil pass's neighbour marks
    glEnable(GL_BLEND);                               // rgb was cleared to 0: draws add up
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    frame.bindGBuffer();
    bindPyramid();
    setCommonUniforms(program);
    // VPLs and clusters written by compute passes must be visible to this pass's SSBO and uniform-block reads.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
    for (int i = 0; i < draws; ++i) {
        if (setupDraw) setupDraw(program, i);
        program.use();
        frame.drawFullscreen();
    }
    glDisable(GL_BLEND);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glStencilMask(0xFF);
    glDisable(GL_STENCIL_TEST);
}

int MultiresGather::loopBudget()
{
    return softwareRasterizer() ? 60000 : std::numeric_limits<int>::max(); // 65535 less the shader's other loops
}

void MultiresGather::upsample(Frame& frame, PassTimers& timers)
{
    auto t = timers.scope("upsample");
    frame.bindGBuffer();
    bindPyramid();
    illumination_.bind(kIlluminationUnit);
    frame.indirect().bindImage(0, GL_WRITE_ONLY, 0, GL_RGBA32F);
    setCommonUniforms(upsample_);
    upsample_.use();
    // The gather rendered into the illumination buffer; the upsampling fetches it as a texture.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    glDispatchCompute(GLuint(ceilDiv(width_, 8)), GLuint(ceilDiv(height_, 8)), 1);
    // The composite (and any read-back) samples the indirect texture.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void MultiresGather::run(Frame& frame, const Buffer& vpls, int vplCount, PassTimers& timers)
{
    buildPyramid(frame, timers);
    markValidFragments(frame, timers);
    // One additive draw per uniform block of the cache (vpl_gather.h); one with no VPLs clears nothing.
    gather(frame, cacheGather_, timers, std::max(vplBlockCount(vplCount), 1),
           [&](Program& p, int block) { p.set("vplCount", bindVplBlock(vpls, block, vplCount)); });
    upsample(frame, timers);
}

int MultiresGather::refine(Frame& frame, PassTimers& timers)
{
    auto t = timers.scope("refine");
    const std::size_t pixels = std::size_t(width_) * std::size_t(height_);
    constexpr std::size_t kVertexBytes = 32; // glsl/technique/isr/multires_refine.comp: SplatVertex
    if (!splatVertices_ || splatVertices_.bytes() < pixels * kVertexBytes) {
        // Work lists and vertices for the worst case, every pixel a fragment.
        refine_ = Program::compute("multires.refine", "technique/isr/multires_refine.comp");
        splat_ = Program::graphics("multires.splat", "technique/isr/multires_splat.vert", "technique/isr/multires_splat.frag",
                                   vplBlockDefines());
        workLists_[0] = Buffer("multires.refine.work0", pixels * sizeof(unsigned));
        workLists_[1] = Buffer("multires.refine.work1", pixels * sizeof(unsigned));
        refineCounts_ = Buffer("multires.refine.counts", 2 * sizeof(unsigned));
        splatVertices_ = Buffer("multires.splat.vertices", pixels * kVertexBytes);
        splatVao_ = VertexArray("multires.splat");
        glVertexArrayVertexBuffer(splatVao_.id(), 0, splatVertices_.id(), 0, GLsizei(kVertexBytes));
        for (unsigned a = 0; a < 2; ++a) {
            glEnableVertexArrayAttrib(splatVao_.id(), a);
            glVertexArrayAttribFormat(splatVao_.id(), a, 4, GL_FLOAT, GL_FALSE, 16 * a);
            glVertexArrayAttribBinding(splatVao_.id(), a, 0);
        }
    }
    counts_.clearToZero();
    refineCounts_.clearToZero();
    const float zero[4] = {0, 0, 0, 0};
    illumination_.clear(0, zero);
    frame.bindGBuffer();
    bindPyramid();
    counts_.bindBase(GL_SHADER_STORAGE_BUFFER, kCountsBinding);
    refineCounts_.bindBase(GL_SHADER_STORAGE_BUFFER, 16);
    splatVertices_.bindBase(GL_SHADER_STORAGE_BUFFER, 17);
    illumination_.bindImage(0, GL_WRITE_ONLY);
    setCommonUniforms(refine_);
    refine_.use();
    // CoarseImageSampling: every patch of the coarsest level; then one pass per finer level over the
    // children of the patches the pass before subdivided. The next pass's size is read back, as [NW09]'s
    // geometry-shader refinement learns its output's length.
    int in = -1, current = 0;
    for (int level = levels_; level >= 0; --level) {
        const int count = in < 0 ? rects_[level].z * rects_[level].w : in;
        workLists_[current].bindBase(GL_SHADER_STORAGE_BUFFER, 14);
        workLists_[1 - current].bindBase(GL_SHADER_STORAGE_BUFFER, 15);
        refine_.set("level", level);
        refine_.set("inCount", in);
        glDispatchCompute(GLuint((count + 63) / 64), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        unsigned next = 0;
        refineCounts_.download(0, sizeof next, &next);
        if (next == 0) break;
        const unsigned reset = 0;
        refineCounts_.update(0, sizeof reset, &reset);
        in = int(next);
        current = 1 - current;
    }
    unsigned counts[2] = {0, 0};
    refineCounts_.download(0, sizeof counts, counts);
    splatCount_ = int(counts[1]);
    // The splat reads the vertices as attributes, the upsampling the marks as a texture.
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    return splatCount_;
}

void MultiresGather::splat(Frame& frame, const Buffer& vpls, int vplCount, PassTimers& timers)
{
    auto t = timers.scope("splat");
    fbo_.bind();
    glViewport(0, 0, illumination_.width(), illumination_.height());
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE); // alpha keeps the refinement's marks
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    splat_.set("bufferSize", glm::vec2(illumination_.width(), illumination_.height()));
    splat_.use();
    splatVao_.bind();
    glMemoryBarrier(GL_UNIFORM_BARRIER_BIT); // VPLs written by compute passes
    // For each VPL, one point per valid fragment: instances are VPLs, one draw per block of the cache.
    for (int block = 0; block < vplBlockCount(vplCount) && splatCount_ > 0; ++block)
        glDrawArraysInstanced(GL_POINTS, 0, splatCount_, bindVplBlock(vpls, block, vplCount));
    glDisable(GL_BLEND);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

std::vector<int> MultiresGather::fragmentsPerLevel() const
{
    std::vector<unsigned> raw(kMaxLevels, 0u);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // the stencil pass's atomic adds
    counts_.download(0, raw.size() * sizeof(unsigned), raw.data());
    return std::vector<int>(raw.begin(), raw.begin() + levels_ + 1);
}

std::vector<Counter> MultiresGather::counters() const
{
    std::vector<Counter> out;
    double total = 0.0;
    const std::vector<int> perLevel = fragmentsPerLevel();
    for (int l = 0; l < int(perLevel.size()); ++l) {
        out.push_back({"fragments.level" + std::to_string(l), double(perLevel[l])});
        total += perLevel[l];
    }
    out.push_back({"fragments.total", total});
    return out;
}

} // namespace bounce::gl
