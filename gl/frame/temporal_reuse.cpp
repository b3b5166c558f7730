#include "gl/frame/temporal_reuse.h"

#include <stdexcept>
#include <string>

#include "gl/frame/bindings.h"
#include "gl/gl.h"
#include "gl/resource/pass_state.h"

namespace bounce::gl {

namespace {

void copyTexture(const Texture& from, const Texture& to)
{
    glCopyImageSubData(from.id(), GL_TEXTURE_2D, 0, 0, 0, 0, to.id(), GL_TEXTURE_2D, 0, 0, 0, 0, from.width(),
                       from.height(), 1);
}

} // namespace

TemporalReuse::TemporalReuse() : TemporalReuse(TemporalReuseSettings{})
{}

TemporalReuse::TemporalReuse(const TemporalReuseSettings& s) : settings(s)
{}

Program& TemporalReuse::program()
{
    // The settings that choose a shader's code are its defines, not uniforms: llvmpipe runs a branch on a
    // uniform that is off at full cost (the unused clamp's nine fetches cost 0.6 ms at 256x256).
    Program& p = programs_[(settings.catmullRom ? 1 : 0) + (settings.clamp ? 2 : 0)];
    if (!p) {
        std::vector<Define> defines;
        if (settings.catmullRom) defines.push_back({"CATMULL_ROM", "1"});
        if (settings.clamp) defines.push_back({"CLAMP_HISTORY", "1"});
        p = Program::graphics("temporal", "frame/fullscreen.vert", "frame/temporal_reuse.frag", defines);
    }
    return p;
}

void TemporalReuse::reset()
{
    valid_ = false;
}

void TemporalReuse::allocate(int width, int height, std::size_t signals)
{
    histories_.clear();
    histories_.resize(signals);
    for (std::size_t i = 0; i < signals; ++i)
        for (int k = 0; k < 2; ++k) {
            const std::string name = "temporal.history" + std::to_string(i) + "." + std::to_string(k);
            histories_[i].value[k] = Texture::create2D(name, GL_RGBA32F, width, height);
            histories_[i].length[k] = Texture::create2D(name + ".length", GL_R32F, width, height);
        }
    previousGeometry_ = Texture::create2D("temporal.previous-geometry", GL_RG32UI, width, height);
    width_ = width;
    height_ = height;
    valid_ = false;
}

void TemporalReuse::apply(const Frame& frame, const std::vector<Texture*>& signals, PassTimers& timers)
{
    const int w = frame.width(), h = frame.height();
    for (const Texture* s : signals)
        if (!s || s->width() != w || s->height() != h || s->internalFormat() != GL_RGBA32F)
            throw std::invalid_argument("temporal reuse: a signal must be RGBA32F at the frame's " + std::to_string(w) +
                                        "x" + std::to_string(h));
    if (!(settings.alpha > 0.0f && settings.alpha <= 1.0f))
        throw std::invalid_argument("temporal reuse: alpha must be in (0, 1]");
    if (signals.empty()) return;
    if (w != width_ || h != height_ || signals.size() != histories_.size()) allocate(w, h, signals.size());

    // temporal_reuse.frag per pixel and signal: its G-buffer texel and its eight neighbours', the current
    // value, four previous G-buffer, history and length texels, with the clamp the 3x3 current neighbourhood
    // (its centre cached);
    // writes the blend and the length. Per scope: the blend copied over each signal (read and write), the
    // G-buffer copied for the next frame.
    const double pixels = double(w) * double(h);
    const bool clamp = settings.clamp;
    // With catmullRom, where the four are all kept (most pixels), the twelve texels around them: each one's
    // G-buffer texel against this pixel's own surface and its history (about 20 flops), and the cubic's
    // weights (about 40).
    const int outer = settings.catmullRom ? 12 : 0;
    PassCost cost;
    // The neighbourhood test: eight more G-buffer texels, nine points projected with their screen motion
    // (about 34 flops each) and each tap's depth, normal and motion against nine (about 16 flops each).
    cost.flops = 120 + 9 * 34 + 4 * 9 * 16 + (clamp ? 9 * 6 : 0) + (outer ? 40 + outer * 20 : 0);
    cost.fetches = 2 + 8 + 4 * 3 + (clamp ? 8 : 0) + outer * 2;
    cost.bytesRead = 8 + 16 + 8 * 8 + 4 * (8 + 16 + 4) + (clamp ? 8 * 16 : 0) + outer * (8 + 16);
    cost.bytesWritten = 16 + 4;
    cost.bytesFixed = pixels * (2 * 16 * (valid_ ? double(signals.size()) : 0.0) + 2 * 8);
    auto scope = timers.scope("temporal", cost);

    frame.bindGBuffer();
    previousGeometry_.bind(UNIT_TEMPORAL_PREVIOUS_GEOMETRY);
    Program& p = program();
    p.set("previousViewProjection", previousViewProjection_);
    p.set("currentJitter", frame.sampler().jitter());
    p.set("hasHistory", valid_ ? 1 : 0);
    p.set("alpha", settings.alpha);
    p.set("depthTolerance", settings.depthTolerance);
    p.set("normalTolerance", settings.normalTolerance);
    p.use();
    fbo_.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1});
    for (std::size_t i = 0; i < signals.size(); ++i) {
        History& history = histories_[i];
        const int read = history.latest, write = 1 - history.latest;
        scope.expectFragments(w, h);
        fbo_.attach(GL_COLOR_ATTACHMENT0, history.value[write]);
        fbo_.attach(GL_COLOR_ATTACHMENT1, history.length[write]);
        PassState::fullscreen(fbo_, w, h).apply();
        signals[i]->bind(UNIT_TEMPORAL_CURRENT);
        history.value[read].bind(UNIT_TEMPORAL_HISTORY);
        history.length[read].bind(UNIT_TEMPORAL_HISTORY_LENGTH);
        frame.drawFullscreen();
        // Without a history the blend is the signal itself: nothing to copy back.
        if (valid_) copyTexture(history.value[write], *signals[i]);
        history.latest = write;
    }
    copyTexture(frame.geometry(), previousGeometry_);
    // Without the frame's sub-pixel jitter (FrameSampler::jitter): the history is kept at pixel centres,
    // and the pass takes the current jitter off the reprojected point, so that a still camera whose frames
    // jitter reads each history texel where it was written (a jittered matrix would resample the history
    // bilinearly every frame and blur it, the emitters' edges over their surroundings most of all).
    previousViewProjection_ = frame.camera().projection(float(w) / float(h)) * frame.view();
    valid_ = true;
}

} // namespace bounce::gl
