// Image-space adaptive sampling (Maletz, Wang & Bowers 2011, §3.3; glsl/frame/points/adaptive*.{glsl,
// comp}): shared by the point-based gathers. Level 0 gathers at the 4 x 4 grid; levels 1 and 2 gather at
// the 2 x 2 and 1 x 1 grids' pixels whose coherence metric exceeds epsilon (0.3, doubled per level) and
// interpolate the others by joint bilateral weights; compose takes both parts through §4's post-process
// joint bilateral filter (7 x 7, or 3 x 3 in glossy scenes), multiplies the diffuse part by each pixel's
// diffuse colour and adds the glossy part, averaged over frames in progressive mode. Passes (summed over
// the levels): "adaptive-select", the technique's "gather", "interpolate", "compose".
//
//   for (int level = 0; level < pixels.levels(); ++level) {
//       const int n = pixels.select(frame, level, timers);
//       pixels.bindForGather(frame, program);   // the targets for glsl/frame/points/gather_target.glsl
//       dispatchPerTarget(program, n, group);
//       pixels.interpolate(frame, level, timers);
//   }
//   pixels.compose(frame, weight, timers);
#pragma once

#include "gl/frame/frame.h"
#include "gl/frame/points/pixel_gather.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

struct AdaptiveSettings {
    bool adaptive = true; // false: gather at every pixel (one level)
    float epsilon = 0.3f; // the first refinement's threshold (§3.3: 0.3), doubled per level
    float lambda = 8.0f;  // the radiance term's weight (§3.3: 8)
    // The post-filter's half-width r, a (2r + 1)^2 window; 0: none; -1: §4's window (7 x 7, 3 x 3 in a glossy
    // scene) at the paper's 512 x 512, scaled with the image's smaller side (r = 3 or 1 at 512, 0 below 171
    // or 512 pixels), so that it covers the same share of the image.
    int postFilter = 0;
    bool glossyScene = false; // for postFilter -1
};

class AdaptivePixels {
public:
    AdaptivePixels(Frame& frame, const AdaptiveSettings& settings);

    int levels() const { return settings_.adaptive ? 3 : 1; }
    int postFilterRadius() const; // r at the current image size
    // "adaptive-select": the pixels to gather at on this level, listed; returns how many.
    int select(Frame& frame, int level, PassTimers& timers);
    // The targets, G-buffer and light images, and gather_target.glsl's uniforms.
    void bindForGather(Frame& frame, Program& program);
    // "interpolate": this level's candidates that were not sampled (nothing on level 0).
    void interpolate(Frame& frame, int level, PassTimers& timers);
    // "compose": frame.indirect() = c_diff x diffuse + glossy (each through the post-filter), blended into
    // the running mean with `newWeight` (1 without progressive accumulation).
    void compose(Frame& frame, float newWeight, PassTimers& timers);
    void setThresholds(float epsilon, float lambda)
    {
        settings_.epsilon = epsilon;
        settings_.lambda = lambda;
    }

    int sampledLastFrame() const { return sampled_; } // gather targets over every level of the last frame

    // The log-average luminance of the frame's light (direct plus L_o) at the pixels gathered so far (the
    // first level's, when select() asks for it on level 1), which display-scales the coherence metric's
    // L_o: a reduction on the GPU (adaptive_mean.comp), 16 bytes read back; and the same from the four
    // images read back, for tests. The light images and the pixels' states, for tests to fill and read.
    float logAverageLuminance(Frame& frame);
    float logAverageLuminanceOnCpu(Frame& frame) const;
    Texture& diffuseLight() { return diffuse_; }
    Texture& glossyLight() { return glossy_; }
    const Texture& pixelState() const { return state_; } // r8ui: adaptive.glsl's kSampled, kInterpolated...

private:
    AdaptiveSettings settings_;
    int width_ = 0, height_ = 0;
    Program select_, interpolate_, compose_, mean_, meanFinal_;
    Texture state_, diffuse_, glossy_, accumulated_, partials_;
    Buffer targets_; // the gather list (pixel_gather.h)
    int sampled_ = 0;
    int selected_ = 0;        // targets of the last select(), its level's alone
    float logAverage_ = 0.0f; // logAverageLuminance() of the first level's samples
    void allocate(int width, int height);
    void setCommon(Frame& frame, Program& program, int spacing);
};

} // namespace bounce::gl
