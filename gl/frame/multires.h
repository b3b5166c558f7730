// The multiresolution eye-space pyramid and its joint bilateral upsampling (Nichols, Shopf & Wyman 2009,
// §3.2.1-3.2.2, after Nichols & Wyman 2009 [NW09]): a frame service for every technique that computes
// light at a subset of pixels, one per multiresolution patch, and upsamples it. Passes:
//   "minmax-mipmap"  eye-space depth / normal min-max pyramid of the G-buffer, with the patch means
//                    (position, normal, diffuse colour) a technique shades (Fig. 2b-c), one compute
//                    dispatch per level; glsl/frame/multires_minmax.comp
//   "upsample"       every pixel takes the valid fragment covering it in a flattened illumination buffer,
//                    interpolated among same-surface neighbours of its level, times the full-resolution
//                    diffuse colour, into frame.indirect(); glsl/frame/multires_upsample.glsl, as a fragment
//                    pass on a software rasteriser and a compute pass on a GPU (see upsampleAsFragments_)
// Layout of the levels and of the flattened buffer, the discontinuity test, the valid-fragment rule and the
// same-surface rule: glsl/common/multires.glsl. Choosing the valid fragments and computing their light is
// the technique's part (image-space radiosity: a stencil pass and a stenciled gather, gl/technique/isr/).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/frame/frame.h"
#include "gl/frame/params.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

struct MultiresSettings {
    // A patch is a discontinuity (needs subdividing) when (max d - min d) >= depthThreshold * min d over
    // its pixels' eye depths d (relative: the same threshold holds near and far), or when any component
    // of its unit normals spans >= normalThreshold. 0 forces full resolution (every pixel at level 0).
    float depthThreshold = 0.02f;
    float normalThreshold = 0.15f;
    // Coarsest patches: 2^coarsestLevel pixels per side. kAutoLevel: the paper's coarsest buffer of 64 x 64
    // patches (§2: "coarse 64^2 pixel clusters"; 16 x 16 pixels at its 1024^2, 8 x 8 at 512^2): the
    // finest level with at least 64 patches across the image's longer side (autoCoarsestLevel).
    static constexpr int kAutoLevel = -1;
    int coarsestLevel = kAutoLevel;
};

// The eye-space parameters every technique built on the pyramid declares: depthThreshold,
// normalThreshold, coarsestLevel (aggregate rows in ParamDecl's field order).
std::vector<ParamDecl> multiresParams();
MultiresSettings multiresSettingsFrom(const ParamValues& values);

class MultiresPyramid {
public:
    static constexpr int kMaxLevels = 16; // glsl/common/multires.glsl: MULTIRES_MAX_LEVELS

    MultiresPyramid(int width, int height, const MultiresSettings& settings);

    // Reallocates for a new image size; true when it did (buffers laid out like flattenedSize() must follow).
    bool resize(int width, int height);
    // "minmax-mipmap": levels 1..coarsestLevel() from the frame's G-buffer (resizes first if needed).
    void build(Frame& frame, PassTimers& timers);
    // "upsample": frame.indirect() from `illumination`, a flattenedSize() RGBA32F texture holding at each
    // valid fragment rgb the light without the receiver's diffuse colour and alpha 1 + the mask of the
    // neighbours it may be interpolated with (glsl/common/multires.glsl: sameSurfaceNeighbours), and
    // alpha 0 elsewhere. `unmodulated`, when given (same size, RGBA32F), is interpolated with the same
    // weights and added without the diffuse colour: glossy reflected radiance.
    void upsample(Frame& frame, const Texture& illumination, PassTimers& timers, const Texture* unmodulated = nullptr);
    // Which stage runs the upsampling (the default: fragments on a software rasteriser, compute on a GPU);
    // the two write the same image (tests/gl/isr_multires_test.cpp).
    void setUpsampleAsFragments(bool asFragments)
    {
        if (asFragments == upsampleAsFragments_) return;
        upsampleAsFragments_ = asFragments;
        upsample_ = upsampleProgram(asFragments, false);
        upsampleUnmodulated_ = Program();
    }
    bool upsampleAsFragments() const { return upsampleAsFragments_; }
    // Level l's rectangle in the flattened buffer as a viewport (origin, size), for passes drawn level by
    // level over it (the stencil pass and the gathers of image-space radiosity).
    glm::ivec4 levelViewport(int level) const { return levelRect(level); }

    // Binds the pyramid textures (units UNIT_MULTIRES_FIRST + 0..5, gl/frame/bindings.h) and sets the layout and threshold
    // uniforms of glsl/common/multires.glsl on `program`.
    void bind() const;
    void setUniforms(Program& program) const;
    // New discontinuity thresholds for the next build (uniforms: nothing is reallocated or recompiled).
    void setThresholds(float depthThreshold, float normalThreshold)
    {
        settings_.depthThreshold = depthThreshold;
        settings_.normalThreshold = normalThreshold;
    }

    const MultiresSettings& settings() const { return settings_; }
    int width() const { return width_; }
    int height() const { return height_; }
    // Levels actually used: coarsestLevel, or fewer when one patch already covers the whole image.
    int coarsestLevel() const { return levels_; }
    // Where level l lies in the flattened buffer: origin (x, y) and size (w, h) in texels.
    glm::ivec4 levelRect(int level) const { return rects_.at(std::size_t(level)); }
    // Size of the flattened buffer: every level side by side.
    glm::ivec2 flattenedSize() const { return flattened_; }

private:
    MultiresSettings settings_;
    int width_ = 0, height_ = 0, levels_ = 0;
    glm::ivec2 flattened_{0};
    std::vector<glm::ivec4> rects_;
    Texture position_, normal_, diffuse_, depth_, normalMin_, normalMax_;
    Framebuffer upsampleFbo_;
    Program reduceFromGBuffer_, reduce_;
    // The upsampling as a fragment pass on a software rasteriser (llvmpipe stores a compute pass's images
    // lane by lane: 0.81 of the compute pass's time as fragments), as a compute pass on a GPU (an H200:
    // 0.019 ms against 0.098 as fragments). Both from frame/multires_upsample.glsl.
    bool upsampleAsFragments_;
    Program upsample_, upsampleUnmodulated_;
    static Program upsampleProgram(bool asFragments, bool unmodulated);
};

// Layout of the flattened buffer for a width x height image with at most `coarsestLevel` levels above
// the pixels: level 0 (the image) at the left, level l >= 1 (ceil(w / 2^l) x ceil(h / 2^l) patches)
// stacked bottom-up in one column to its right. Exposed for tests.
std::vector<glm::ivec4> multiresLevelRects(int width, int height, int coarsestLevel);
// The coarsest level of MultiresSettings::kAutoLevel: the largest l with ceil(max(width, height) / 2^l)
// >= 64 (0 for images under 127 pixels across).
int autoCoarsestLevel(int width, int height);

} // namespace bounce::gl
