#include "gl/technique/isr/multires_gather.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "gl/context/context.h"
#include "gl/gl.h"
#include "gl/probe/machine_probe.h"
#include "gl/resource/dispatch.h"
#include "gl/resource/pass_state.h"
#include "gl/technique/isr/bindings.h"
#include "gl/technique/isr/vpl_gather.h"

namespace bounce::gl {

MultiresGather::MultiresGather(Frame& frame, const MultiresSettings& settings, bool asFragments)
    : pyramid_(frame.width(), frame.height(), settings),
      fbo_("multires.fbo"),
      counts_("multires.fragmentCounts", sizeof(unsigned) * kMaxLevels),
      asFragments_(asFragments),
      stencilSetup_(
          Program::graphics("multires.stencil", "frame/fullscreen.vert", "technique/isr/multires_stencil.frag")),
      cacheGather_(gatherProgram("multires.gather", "technique/isr/multires_gather.frag",
                                 "technique/isr/multires_gather.comp", vplBlockDefines()))
{
    allocate();
}

Program MultiresGather::gatherProgram(const std::string& label, const std::string& fragmentPath,
                                      const std::string& computePath, const std::vector<Define>& defines) const
{
    if (asFragments_) return Program::graphics(label, "frame/fullscreen.vert", fragmentPath, defines);
    return Program::compute(label, computePath, defines);
}

bool MultiresGather::defaultGatherAsFragments()
{
    return preferFragmentPasses();
}

ParamDecl MultiresGather::gatherFormParam()
{
    return choiceParam("gather", {"auto", "fragments", "compute"}, 0,
                       "the gather's form: fragments (the paper's stenciled quad) or compute (the valid fragments "
                       "listed, one invocation each); auto: the faster form by this renderer's `bounce probe` "
                       "ceilings, else fragments on a software rasteriser and compute on a GPU, whose graphics "
                       "units may be few");
}

bool MultiresGather::gatherAsFragmentsFrom(const ParamValues& values, const std::vector<ParamDecl>& decls)
{
    const std::string form = values.getChoice(decls, "gather");
    return form == "auto" ? defaultGatherAsFragments() : form == "fragments";
}

void MultiresGather::allocate()
{
    // The flattened multiresolution illumination buffer and its stencil (§3.2.1), laid out as the pyramid's.
    const glm::ivec2 size = pyramid_.flattenedSize();
    illumination_ = Texture::create2D("multires.illumination", GL_RGBA32F, size.x, size.y);
    stencil_ = Texture::create2D("multires.stencil", GL_DEPTH24_STENCIL8, size.x, size.y);
    fbo_.attach(GL_COLOR_ATTACHMENT0, illumination_);
    fbo_.attach(GL_DEPTH_STENCIL_ATTACHMENT, stencil_);
    fbo_.setDrawBuffers({GL_COLOR_ATTACHMENT0});
    fbo_.checkComplete();
    validList_ = Buffer();
}

void MultiresGather::buildPyramid(Frame& frame, PassTimers& timers)
{
    if (pyramid_.resize(frame.width(), frame.height())) allocate();
    pyramid_.build(frame, timers);
}

void MultiresGather::drawLevels(Program& program, PassState state, const std::function<void(int)>& perLevel)
{
    program.use();
    fullscreenVao_.bind();
    for (int level = 0; level <= pyramid_.coarsestLevel(); ++level) {
        state.viewport = pyramid_.levelViewport(level);
        state.apply();
        program.set("drawLevel", level);
        if (perLevel) perLevel(level);
        glDrawArrays(GL_TRIANGLES, 0, 3); // frame/fullscreen.vert's triangle, clipped to the level's viewport
    }
}

void MultiresGather::markValidFragments(Frame& frame, PassTimers& timers)
{
    // multires_stencil.frag per patch of a level: two patch states; for a valid fragment its marks and
    // stencil, and above level 0 its eight neighbours' states and ranges (five texels each). The valid
    // fragments are the last frame's counts (this frame's arrive with the pass's queries).
    PassCost cost;
    cost.flops = 20;
    cost.fetches = 2;
    cost.bytesRead = 2 * 8;
    const double flattened = double(illumination_.width()) * illumination_.height();
    cost.bytesFixed = flattened * (16 + 4); // the clears
    double validCoarse = 0.0, valid = 0.0;
    for (std::size_t l = 0; l < lastValid_.size(); ++l) {
        valid += lastValid_[l];
        if (l > 0) validCoarse += lastValid_[l];
    }
    cost.bytesFixed += valid * (16 + 4) + validCoarse * 8 * 5 * 8;
    cost.fetchesFixed = validCoarse * 8 * 5;
    cost.flopsFixed = validCoarse * 8 * 20;
    auto t = timers.scope("stencil-setup", cost);
    // A triangle over each level's viewport (drawLevels), the shader at every fragment of it: the stencil
    // marks the fragments the shader keeps, after it ran.
    for (int level = 0; level <= pyramid_.coarsestLevel(); ++level) {
        const glm::ivec4 v = pyramid_.levelViewport(level);
        t.expectFragments(v.z, v.w, v.x, v.y);
    }
    PassState state = PassState::fullscreen(fbo_, illumination_.width(), illumination_.height());
    state.stencil.test = true;
    state.stencil.ref = 1;
    state.stencil.depthPass = GL_REPLACE; // the fragments that survive the shader set the stencil to 1
    state.apply();                        // before the clears, which obey the write masks
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfi(fbo_.id(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
    frame.bindGBuffer();
    pyramid_.bind();
    pyramid_.setUniforms(stencilSetup_);
    while (int(validQueries_.size()) <= pyramid_.coarsestLevel())
        validQueries_.emplace_back(GL_SAMPLES_PASSED,
                                   "multires.validFragments." + std::to_string(validQueries_.size()));
    // Every fragment the shader keeps is a valid one (the rest are discarded): the samples that pass are
    // the level's valid fragments, counted without a shader atomic.
    drawLevels(stencilSetup_, state, [&](int level) {
        if (level > 0) validQueries_[std::size_t(level - 1)].end();
        validQueries_[std::size_t(level)].begin();
    });
    validQueries_[std::size_t(pyramid_.coarsestLevel())].end();
    countsFromQueries_ = true;
}

void MultiresGather::gather(Frame& frame, Program& program, PassTimers& timers, int draws,
                            const std::function<void(Program&, int)>& setupDraw, const PassCost& perFragment,
                            int invocationsPerFragment)
{
    // The quad: the stencil test masks the shader of every fragment that is not valid, but the driver may
    // count those as invocations (llvmpipe counts the whole flattened buffer): the work is the valid
    // fragments' (the stencil pass's own counts), and each invocation only blends. The list: one read of
    // every texel's marks, then per valid fragment its entry, and per dispatch the entry again and its
    // texel read and written; invocations past the list do nothing.
    const double flattened = double(illumination_.width()) * illumination_.height();
    PassCost perInvocation;
    if (asFragments_) {
        perInvocation.bytesRead = 16;
        perInvocation.bytesWritten = 16;
    } else {
        perInvocation.bytesFixed = flattened * 16;
    }
    auto t = timers.scope("gather", perInvocation);
    // The list: a dispatch over the flattened buffer, then one of the longest list per draw. The quad
    // declares nothing: whether the stencil test masks a fragment's shader before it runs (and is counted)
    // is the driver's choice, between the valid fragments and the whole buffer.
    if (!asFragments_)
        t.expectComputes(computeInvocations({illumination_.width(), illumination_.height(), 1}, {8, 8, 1}) +
                         draws * rowsInvocations(listGroups(invocationsPerFragment), 64));
    const double valid = asFragments_ ? gatherAsQuad(frame, program, draws, setupDraw)
                                      : gatherAsList(frame, program, draws, setupDraw, invocationsPerFragment);
    PassCost work = kernelWork(valid * draws, perFragment);
    if (!asFragments_) work.bytesFixed += valid * (4 + 4 * draws);
    t.addWork(work);
}

double MultiresGather::gatherAsQuad(Frame& frame, Program& program, int draws,
                                    const std::function<void(Program&, int)>& setupDraw)
{
    PassState state = PassState::fullscreen(fbo_, illumination_.width(), illumination_.height());
    state.stencil.test = true;
    state.stencil.func = GL_EQUAL; // only the valid multiresolution fragments (§3.2.1)
    state.stencil.ref = 1;
    state.stencil.writeMask = 0x00;
    state.colorMask = {true, true, true, false}; // alpha keeps the stencil pass's neighbour marks
    state.blend = true;                          // additive; rgb was cleared to 0: draws add up
    state.apply();
    frame.bindGBuffer();
    pyramid_.bind();
    pyramid_.setUniforms(program);
    // VPLs and clusters written by compute passes must be visible to this pass's SSBO and uniform-block reads.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
    state.apply();
    fullscreenVao_.bind();
    for (int i = 0; i < draws; ++i) {
        if (setupDraw) setupDraw(program, i);
        program.use();
        glDrawArrays(GL_TRIANGLES, 0, 3); // the paper's one quad over the flattened buffer
    }
    // After the draws are issued, so that waiting for the stencil pass's counts stalls nothing queued.
    double valid = 0.0;
    for (int n : fragmentsPerLevel()) valid += n;
    return valid;
}

double MultiresGather::gatherAsList(Frame& frame, Program& program, int draws,
                                    const std::function<void(Program&, int)>& setupDraw, int invocationsPerFragment)
{
    const int width = illumination_.width(), height = illumination_.height();
    if (!validList_.id()) {
        validList_ = Buffer("multires.validList", sizeof(unsigned) * (1 + std::size_t(width) * std::size_t(height)));
        validListProgram_ = Program::compute("multires.validList", "technique/isr/multires_valid_list.comp");
    }
    // The stencil pass's marks (a framebuffer write) before the list reads them as an image.
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    validList_.clearToZero();
    validList_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_ISR_VALID_LIST);
    illumination_.bindImage(0, GL_READ_ONLY);
    validListProgram_.use();
    glDispatchCompute(GLuint((width + 7) / 8), GLuint((height + 7) / 8), 1);
    frame.bindGBuffer();
    pyramid_.bind();
    pyramid_.setUniforms(program);
    // The list, and the VPLs and clusters written by compute passes, before the gather reads them.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    illumination_.bindImage(0, GL_READ_WRITE);
    // Each dispatch covers the longest list there can be; invocations past its count return at once. In
    // rows of groups (valid_list.glsl: listInvocation).
    const std::size_t groups = listGroups(invocationsPerFragment);
    for (int i = 0; i < draws; ++i) {
        if (setupDraw) setupDraw(program, i);
        dispatchRows(program, groups, 64);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT); // the next dispatch adds to what this one wrote
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT); // the upsampling samples the buffer
    double valid = 0.0;                            // the list holds as many as the stencil pass counted
    for (int n : fragmentsPerLevel()) valid += n;
    return valid;
}

std::size_t MultiresGather::listGroups(int invocationsPerFragment) const
{
    const std::size_t texels = std::size_t(illumination_.width()) * std::size_t(illumination_.height());
    return (texels * std::size_t(std::max(invocationsPerFragment, 1)) + 63) / 64;
}

int MultiresGather::loopBudget()
{
    return softwareRasterizer() ? 60000 : std::numeric_limits<int>::max(); // 65535 less the shader's other loops
}

void MultiresGather::upsample(Frame& frame, PassTimers& timers)
{
    pyramid_.upsample(frame, illumination_, timers);
}

void MultiresGather::run(Frame& frame, const Buffer& vpls, int vplCount, PassTimers& timers)
{
    buildPyramid(frame, timers);
    markValidFragments(frame, timers);
    // One additive draw per uniform block of the cache (vpl_gather.h); one with no VPLs clears nothing.
    // multires_gather.frag per valid fragment and draw: its patch (three texels), the block's VPLs, an
    // additive RGBA32F write.
    const int draws = std::max(vplBlockCount(vplCount), 1);
    PassCost cost;
    cost.flops = 20 + double(vplCount) * kFlopsPerVpl / draws;
    cost.uniformWords = double(vplCount) * kUniformWordsPerVpl / draws;
    cost.fetches = 3;
    cost.bytesRead = 16 + 8 + 8 + 16; // patch texels, blending's read
    cost.bytesWritten = 16;
    gather(
        frame, cacheGather_, timers, draws,
        [&](Program& p, int block) { p.set("vplCount", bindVplBlock(vpls, block, vplCount)); }, cost);
    upsample(frame, timers);
}

int MultiresGather::refine(Frame& frame, PassTimers& timers)
{
    PassCost cost; // multires_refine.comp per patch tested: its state and ranges, one work item or vertex out
    cost.flops = 40;
    cost.fetches = 4;
    cost.bytesRead = 4 * 8;
    cost.bytesWritten = 32;
    auto t = timers.scope("refine", cost);
    const std::size_t pixels = std::size_t(pyramid_.width()) * std::size_t(pyramid_.height());
    constexpr std::size_t kVertexBytes = 32; // glsl/technique/isr/multires_refine.comp: SplatVertex
    if (!splatVertices_ || splatVertices_.bytes() < pixels * kVertexBytes) {
        // Work lists and vertices for the worst case, every pixel a fragment.
        refine_ = Program::compute("multires.refine", "technique/isr/multires_refine.comp");
        splat_ = Program::graphics("multires.splat", "technique/isr/multires_splat.vert",
                                   "technique/isr/multires_splat.frag", vplBlockDefines());
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
    countsFromQueries_ = false;
    refineCounts_.clearToZero();
    const float zero[4] = {0, 0, 0, 0};
    illumination_.clear(0, zero);
    frame.bindGBuffer();
    pyramid_.bind();
    counts_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_ISR_FRAGMENT_COUNTS);
    refineCounts_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_ISR_REFINE_COUNTS);
    splatVertices_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_ISR_SPLAT_VERTICES);
    illumination_.bindImage(0, GL_WRITE_ONLY);
    pyramid_.setUniforms(refine_);
    refine_.use();
    // CoarseImageSampling: every patch of the coarsest level; then one pass per finer level over the
    // children of the patches the pass before subdivided. The next pass's size is read back, as [NW09]'s
    // geometry-shader refinement learns its output's length.
    int in = -1, current = 0;
    for (int level = pyramid_.coarsestLevel(); level >= 0; --level) {
        const glm::ivec4 rect = pyramid_.levelRect(level);
        const int count = in < 0 ? rect.z * rect.w : in;
        workLists_[current].bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_ISR_WORK_IN);
        workLists_[1 - current].bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_ISR_WORK_OUT);
        refine_.set("level", level);
        refine_.set("inCount", in);
        t.expectComputes(computeInvocations({count, 1, 1}, {64, 1, 1}));
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
    // multires_splat.frag per fragment of a splat: one VPL's contribution, an additive write.
    PassCost cost;
    cost.flops = kFlopsPerVpl + 10;
    cost.bytesRead = 16;
    cost.bytesWritten = 16;
    auto t = timers.scope("splat", cost);
    PassState state = PassState::fullscreen(fbo_, illumination_.width(), illumination_.height());
    state.colorMask = {true, true, true, false}; // alpha keeps the refinement's marks
    state.blend = true;                          // additive
    state.apply();
    splat_.set("bufferSize", glm::vec2(illumination_.width(), illumination_.height()));
    splat_.use();
    splatVao_.bind();
    glMemoryBarrier(GL_UNIFORM_BARRIER_BIT); // VPLs written by compute passes
    // For each VPL, one point per valid fragment: instances are VPLs, one draw per block of the cache.
    for (int block = 0; block < vplBlockCount(vplCount) && splatCount_ > 0; ++block)
        glDrawArraysInstanced(GL_POINTS, 0, splatCount_, bindVplBlock(vpls, block, vplCount));
}

std::vector<int> MultiresGather::fragmentsPerLevel() const
{
    const int levels = pyramid_.coarsestLevel() + 1;
    if (countsFromQueries_) {
        std::vector<int> out(std::size_t(levels), 0);
        for (int l = 0; l < levels && l < int(validQueries_.size()); ++l)
            out[std::size_t(l)] = int(validQueries_[l].result());
        lastValid_ = out;
        return out;
    }
    std::vector<unsigned> raw(kMaxLevels, 0u);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // the refinement's atomic adds
    counts_.download(0, raw.size() * sizeof(unsigned), raw.data());
    return std::vector<int>(raw.begin(), raw.begin() + levels);
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
