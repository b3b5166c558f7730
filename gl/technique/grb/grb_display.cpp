#include "gl/technique/grb/grb_display.h"

#include <algorithm>

#include "gl/frame/bindings.h"
#include "gl/gl.h"
#include "gl/resource/pass_state.h"
#include "gl/technique/grb/bindings.h"

namespace bounce::gl {

GrbDisplay::GrbDisplay(const Frame& frame, const RadianceAtlases& radiance, const KBuffer& kbuffer, bool finalGlossy,
                       bool showEmitted)
    : finalGlossy_(finalGlossy),
      showEmitted_(showEmitted),
      displayFbo_("grb.display.fbo"),
      glossyFbo_("grb.finalGlossy.fbo"),
      vao_("grb.display")
{
    std::vector<Define> d = {{"ATLAS_TEXTURES", "1"}};
    if (finalGlossy) d.push_back({"FINAL_GLOSSY", "1"});
    if (showEmitted) d.push_back({"SHOW_EMITTED", "1"});
    display_ = Program::graphics("grb.display", "technique/grb/display.vert", "technique/grb/display.frag", d);
    if (finalGlossy) {
        std::vector<Define> g = radiance.defines();
        for (const Define& r : kbuffer.readerDefines()) g.push_back(r);
        if (showEmitted) g.push_back({"SHOW_EMITTED", "1"});
        gather_ = Program::graphics("grb.finalGlossy", "frame/fullscreen.vert", "technique/grb/final_glossy.frag", g);
    }
    allocate(frame);
}

void GrbDisplay::allocate(const Frame& frame)
{
    width_ = frame.width();
    height_ = frame.height();
    depth_ = Texture::create2D("grb.display.depth", GL_DEPTH_COMPONENT32F, width_, height_);
    displayFbo_.attach(GL_DEPTH_ATTACHMENT, depth_);
    if (finalGlossy_) {
        glossySum_ = Texture::create2D("grb.finalGlossy", GL_RGBA32F, width_, height_);
        glossyFbo_.attach(GL_COLOR_ATTACHMENT0, glossySum_);
        glossyFbo_.checkComplete();
    }
    clear();
}

void GrbDisplay::clear()
{
    const float zero[4] = {0, 0, 0, 0};
    if (finalGlossy_) glossySum_.clear(0, zero);
}

void GrbDisplay::gatherFinalGlossy(const Frame& frame, const GrbAtlas& atlas, const RadianceAtlases& radiance,
                                   const KBuffer& kbuffer, const BundleView& view, PassTimers& timers)
{
    if (!finalGlossy_) return;
    if (frame.width() != width_ || frame.height() != height_) allocate(frame);
    // final_glossy.frag per pixel: its G-buffer texels (geometry, diffuse, specular) and camera block (12
    // words); where glossy (a bound: every pixel) the view direction, bundleSender, one sender's radiance, the
    // lobe, and the RGBA32F sum blended (read and written).
    const PassCost sender = kbuffer.bundleSenderCost(false), sent = radiance.senderRadianceCost();
    PassCost cost;
    cost.flops = 42 + 11 + 95 + sender.flops + sent.flops;
    cost.fetches = 3 + sender.fetches + sent.fetches;
    cost.bytesRead = 3 * 8 + 16 + sender.bytesRead + sent.bytesRead;
    cost.bytesWritten = 16;
    cost.uniformWords = 12;
    auto t = timers.scope("final-glossy", cost);
    t.expectFragments(width_, height_);
    PassState s = PassState::fullscreen(glossyFbo_, width_, height_);
    s.blend = true; // sums over directions, the count in alpha
    s.apply();
    frame.bindGBuffer();
    frame.bindSceneData();
    atlas.bind();
    kbuffer.bindForRead();
    radiance.bindSender();
    KBuffer::setBundleUniforms(gather_, view);
    gather_.set("atlasWidth", atlas.width());
    gather_.set("cameraPosition", frame.camera().position);
    gather_.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void GrbDisplay::display(Frame& frame, const GrbAtlas& atlas, const RadianceAtlases& radiance, PassTimers& timers)
{
    if (frame.width() != width_ || frame.height() != height_) allocate(frame);
    // display.frag per fragment of the scene from the camera: its G-buffer texels and camera block (12 words),
    // the view direction, four texels of the indirect atlas (showEmitted: and of the direct one) weighted
    // bilinearly, the transmission, with finalGlossy the pixel's glossy sum; one RGBA32F out, the depth test.
    // Per scope the clears, and display.vert per corner its index, position and atlas corner.
    const double pixels = double(width_) * height_, triangles = double(atlas.layout().triangleCount());
    PassCost cost;
    cost.flops = 42 + 11 + 8 + 4 * 16 + 35 + (showEmitted_ ? 4 * 3 : 0) + (finalGlossy_ ? 7 : 0);
    cost.fetches = 3 + 4 + (showEmitted_ ? 4 : 0) + (finalGlossy_ ? 1 : 0);
    cost.bytesRead = 3 * 8 + 4 * 16 + (showEmitted_ ? 4 * 16 : 0) + (finalGlossy_ ? 16 : 0) + 4;
    cost.bytesWritten = 16 + 4;
    cost.uniformWords = 12;
    cost.bytesFixed = pixels * (16 + 4) + 3.0 * triangles * (4 + 12 + 8);
    cost.triangles = triangles;
    auto t = timers.scope("display", cost);
    displayFbo_.attach(GL_COLOR_ATTACHMENT0, frame.indirect());
    displayFbo_.checkComplete();
    PassState s = PassState::fullscreen(displayFbo_, width_, height_);
    s.depthTest = true;
    s.apply();
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(displayFbo_.id(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfi(displayFbo_.id(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
    frame.bindGBuffer();
    frame.bindSceneData();
    atlas.bind();
    radiance.indirect().bind(UNIT_GRB_SENDER_INDIRECT);
    if (showEmitted_) radiance.direct().bind(UNIT_GRB_SENDER_DIRECT);
    if (finalGlossy_) glossySum_.bind(UNIT_GRB_FINAL_GLOSSY);
    display_.set("viewProj", frame.projection() * frame.view());
    display_.set("cameraPosition", frame.camera().position);
    display_.set("atlasWidth", atlas.width());
    display_.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(3 * atlas.layout().triangleCount()));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

KBufferStats::KBufferStats(const KBuffer& kbuffer)
    : stats_("grb.kbuffer.stats", 4 * sizeof(std::uint32_t)), fbo_("grb.kbuffer.stats"), vao_("grb.kbuffer.stats")
{
    program_ = Program::graphics("grb.kbufferStats", "frame/fullscreen.vert", "technique/grb/kbuffer_stats.frag",
                                 kbuffer.readerDefines());
    fbo_.setDefaultSize(kbuffer.size(), kbuffer.size());
    stats_.clearToZero();
}

void KBufferStats::count(const KBuffer& kbuffer, const BundleView& view, PassTimers& timers)
{
    // kbuffer_stats.frag per k-buffer pixel: its count or stencil; Stencil and Peel each of its k entries
    // (Atomic: the count again); up to four atomics on the shared counters (a bound: every pixel occupied and
    // overflowing).
    const bool atomic = kbuffer.capture() == KBufferCapture::Atomic;
    const double k = kbuffer.k();
    PassCost cost;
    cost.flops = 6 + (atomic ? 0 : 3 * k);
    cost.fetches = 1 + (atomic ? 1 : k);
    cost.bytesRead = 4 + (atomic ? 4 : 8 * k) + 4 * 4;
    cost.bytesWritten = 4 * 4;
    auto t = timers.scope("kbuffer-stats", cost);
    t.expectFragments(kbuffer.size(), kbuffer.size());
    PassState::fullscreen(fbo_, kbuffer.size(), kbuffer.size()).apply();
    kbuffer.bindForRead();
    stats_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_GRB_STATS);
    KBuffer::setBundleUniforms(program_, view);
    program_.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    dirty_ = true;
}

KBufferStats::Totals KBufferStats::read()
{
    if (dirty_) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        const std::vector<std::uint32_t> v = stats_.download<std::uint32_t>();
        pending_.overflowPixels = v[0];
        pending_.largestCount = v[1];
        pending_.occupiedPixels = v[2];
        pending_.entries = v[3];
        stats_.clearToZero();
        dirty_ = false;
    } else {
        pending_ = Totals{};
    }
    return pending_;
}

} // namespace bounce::gl
