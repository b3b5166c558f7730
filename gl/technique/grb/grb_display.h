// What the viewer sees of the global ray-bundles (Hermes et al. 2010, Sec. 3 and 5.3): the indirect part
// of the atlas at every pixel, found through the atlas coordinates of the scene rasterised from the camera
// (pass "display"), and the optional final glossy bounce gathered at the G-buffer's pixels per direction
// (pass "final-glossy"). Writes frame.indirect() only; the frame's direct light stays the frame's.
#pragma once

#include <vector>

#include "gl/frame/frame.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"
#include "gl/technique/grb/grb_atlas.h"
#include "gl/technique/grb/kbuffer.h"
#include "gl/technique/grb/radiance_atlases.h"

namespace bounce::gl {

class GrbDisplay {
public:
    // showEmitted (emitters=bundles, Sec. 5.1): the display adds the light the bundles carried from
    // emitting surfaces (the direct atlas) and the final glossy bounce the emitters' glossy reflection, in
    // place of the frame's direct light from emitters (Frame::setAreaLightsInDirect).
    GrbDisplay(const Frame& frame, const RadianceAtlases& radiance, const KBuffer& kbuffer, bool finalGlossy,
               bool showEmitted);

    // Zero the final glossy sums (the camera moved, or the accumulation starts over).
    void clear();
    // Sec. 5.3 for one direction: Eq. 3 towards the eye at every glossy pixel, added to the sums.
    void gatherFinalGlossy(const Frame& frame, const GrbAtlas& atlas, const RadianceAtlases& radiance,
                           const KBuffer& kbuffer, const BundleView& view, PassTimers& timers);
    // The indirect radiance (and with showEmitted the emitters' light) into frame.indirect().
    void display(Frame& frame, const GrbAtlas& atlas, const RadianceAtlases& radiance, PassTimers& timers);

    bool finalGlossy() const { return finalGlossy_; }

private:
    bool finalGlossy_, showEmitted_;
    int width_ = 0, height_ = 0;
    Texture depth_, glossySum_;
    Framebuffer displayFbo_, glossyFbo_;
    Program display_, gather_;
    VertexArray vao_;
    void allocate(const Frame& frame);
};

// Per direction: the k-buffer pixels that overflowed, the largest count, the occupied pixels and entries
// (pass "kbuffer-stats"), summed over the directions since the last read.
class KBufferStats {
public:
    explicit KBufferStats(const KBuffer& kbuffer);
    void count(const KBuffer& kbuffer, const BundleView& view, PassTimers& timers);
    struct Totals {
        std::uint64_t overflowPixels = 0, occupiedPixels = 0, entries = 0;
        std::uint32_t largestCount = 0;
    };
    // The sums since the last read; starts new ones.
    Totals read();

private:
    Buffer stats_;
    Framebuffer fbo_;
    Program program_;
    VertexArray vao_;
    Totals pending_;
    bool dirty_ = false;
};

} // namespace bounce::gl
