// The full-screen VPL gather (Nichols, Shopf & Wyman 2009, §3.2.2, Eqs. 1 and 5) at every pixel of the
// frame, without the multiresolution stencil: what `rsm` and `rsm-full` use, and `isr` until the
// multiresolution gather is wired in. Reads the VPL cache (glsl/technique/isr/vpl.glsl, SSBO binding 8)
// and writes frame.indirect(). No indirect visibility (as in the paper).
#pragma once

#include <string>

#include "gl/frame/frame.h"
#include "gl/resource/buffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

class VplGather {
public:
    // VPLs gathered per dispatch: long gathers (rsm-full) are split so no single dispatch runs for seconds.
    static constexpr int kVplsPerDispatch = 65536;

    VplGather();
    // Gathers VPLs [0, count) of `vpls` into frame.indirect(), timed as `pass`.
    void gather(Frame& frame, const Buffer& vpls, int count, PassTimers& timers, const std::string& pass = "gather");

private:
    Program program_;
};

} // namespace bounce::gl
