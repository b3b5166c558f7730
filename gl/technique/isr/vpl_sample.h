// Regular-grid VPL sampling of the RSM into the VPL cache (the `rsm` / `rsm-full` baselines of Nichols,
// Shopf & Wyman 2009, §3.2.2): each view is cut into side x side blocks, each block one VPL (flux: the
// block's whole reflected flux; position and normal: its lit texel nearest the block centre; solid angle:
// its lit texels'; area: Eq. 3). Pass timed as "vpl-sample".
#pragma once

#include "gl/frame/rsm.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

class VplSampler {
public:
    VplSampler();
    // VPLs per view and per side for about `vpls` VPLs over `views` views of size^2 texels:
    // floor(sqrt(vpls / views)), at least 1 and at most size.
    static int sideFor(int vpls, int views, int size);
    // Bytes of one VPL in the cache (glsl/technique/isr/vpl.glsl).
    static constexpr std::size_t kVplBytes = 48;

    // Writes side^2 x views VPLs to `cache` (which must hold them) and returns their number.
    int sample(const RsmPass& rsm, Buffer& cache, int side, PassTimers& timers);

private:
    Program program_;
};

} // namespace bounce::gl
