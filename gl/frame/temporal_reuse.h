// Temporal reuse (issue 58; Schied et al., "Spatiotemporal Variance-Guided Filtering", HPG 2017, sec. 4.1):
// a signal the frame recomputes every frame at its own resolution (the direct light, a technique's
// indirect light) is blended with its history, the pass's own output of the previous frame, reprojected
// through the previous frame's camera. Each pixel rebuilds its surface point from the G-buffer, projects it
// with the previous view-projection and takes the previous output there from the four nearest texels, each
// kept only where the previous G-buffer saw a surface this pixel or one of its 3x3 neighbours sees now (its
// normal within `normalTolerance`, 1 - cos, of theirs, its eye depth within the span of theirs widened by
// `depthTolerance`, relative: jittered samples of a pixel that straddles two surfaces land on either; a
// neighbour's surface only where the camera moves it on screen as it moves this pixel's own point, within
// 0.15 pixel, so that a surface uncovered by parallax takes nothing of the edge that covered it) and
// held a finite value. Where none is kept (disocclusion, the
// border, background then) the pixel takes the current value and its history restarts. The history, clamped
// to the current signal's 3x3 neighbourhood (min/max, against ghosting; `clamp`), is blended with weight
// max(alpha, 1/n) on the new value, n the frames the history holds, so that the first frames after a
// restart average equally until n reaches 1/alpha. Background pixels pass the current value. With
// `catmullRom` the history is resampled by Catmull-Rom's cubic over the 4x4 texels around the point where
// all sixteen are kept.
// A fragment pass per signal (frame/temporal_reuse.frag), timed as "temporal"; gl/frame/README.md has its
// cost and where it departs from SVGF.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "gl/frame/frame.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

struct TemporalReuseSettings {
    float alpha = 0.2f;           // weight of the new value once the history is 1/alpha frames long (SVGF: 0.2)
    bool clamp = true;            // clamp the history to the current 3x3 neighbourhood's min/max
    float depthTolerance = 0.05f; // |previous eye depth - reprojected eye depth| / reprojected eye depth
    float normalTolerance = 0.1f; // 1 - cos of the angle between the two normals
    // The history resampled by Catmull-Rom's cubic where its 4x4 texels are all kept (else the bilinear
    // blend): a camera moving by fractions of a pixel resamples it every frame, and the bilinear blend blurs
    // it each time.
    bool catmullRom = false;
};

class TemporalReuse {
public:
    TemporalReuse();
    explicit TemporalReuse(const TemporalReuseSettings& settings);

    // Blends each signal (RGBA32F, frame.width() x frame.height(); rgb blended, alpha passed through) with its
    // history and writes the result over it; it becomes that signal's history for the next call. Call after
    // the frame's G-buffer pass, with the signals in the same order every frame. The first call, the first
    // after reset(), and one whose frame size or number of signals differs from the previous call's take
    // no history: the signals come out as they went in, and become the history. Throws std::invalid_argument
    // for a signal of another size or format, or alpha outside (0, 1].
    void apply(const Frame& frame, const std::vector<Texture*>& signals, PassTimers& timers);
    // Drops every history (a scene or light change, a technique switch): the next apply() starts over.
    void reset();
    // Whether the next apply() has a history to reproject (for tests and the demo's panel).
    bool hasHistory() const { return valid_; }

    TemporalReuseSettings settings; // read at every apply()

private:
    struct History {
        Texture value[2];  // RGBA32F: the previous outputs, alternately written
        Texture length[2]; // R32F: frames each texel's value averages (0: background)
        int latest = 0;    // which of the two the last apply() wrote
    };
    Program programs_[4]; // bilinear, Catmull-Rom, each without and with the clamp: compiled when first used
    Framebuffer fbo_{"temporal.fbo"};
    std::vector<History> histories_; // one per signal
    Texture previousGeometry_;       // RG32UI: a copy of the previous frame's gGeometry
    glm::mat4 previousViewProjection_{1.0f};
    int width_ = 0, height_ = 0;
    bool valid_ = false;
    void allocate(int width, int height, std::size_t signals);
    Program& program();
};

} // namespace bounce::gl
