// Stencil-based multiresolution gathering (Nichols, Shopf & Wyman 2009, §3.2): indirect light gathered
// once per multiresolution eye-space patch instead of once per pixel, then upsampled. The pyramid and the
// upsampling are the frame's (gl/frame/multires.h); the stencil refinement and the gather are the
// paper's own part, here. Passes, in order:
//   "minmax-mipmap"  eye-space depth / normal min-max pyramid of the G-buffer, with the patch averages
//                    (position, normal, diffuse colour) the gather shades (§3.2.1, Fig. 2b-c; frame)
//   "stencil-setup"  one pass over the flattened multiresolution buffer that sets the stencil of exactly
//                    the valid fragments (the pseudo code of §3.2.1), counts them per level (an occlusion
//                    query per level) and marks which neighbours each may be interpolated with
//   "gather"         ONE full-screen quad, stencil EQUAL, that gathers light at every valid fragment (the
//                    VPL cache of §3.2.2 by default; hisr plugs in its VPL-tree traversal)
// Departure: the paper draws the stencil pass as one full-screen quad too; here it is one quad per level,
// over that level's rectangle, so that an occlusion query counts each level's valid fragments (instead of
// a shader atomic per fragment) and each fragment knows its level from a uniform. The same fragments run.
// The gathers stay one quad: drawn level by level they took 1.05 (multires-gather) and 1.1 (hisr) times
// as long on llvmpipe (measured).
//   "upsample"       every pixel takes the valid fragment covering it, interpolated among same-level
//                    neighbours [NW09], times the full-resolution diffuse colour, into frame.indirect()
//                    (frame)
// Layout, thresholds and the exact upsampling rule: glsl/common/multires.glsl and the README.
//
// The path §3.2 replaces, multiresolution splatting [NW09], fills the same buffer for the paper's Table 1
// (technique multires-splat): "refine" (iterative subdivision from the coarsest patches, one compute pass
// per level, building the list of valid fragments) and "splat" (that list drawn as points once per VPL,
// added by blending) instead of "stencil-setup" and "gather"; the upsampling is the same.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/frame/frame.h"
#include "gl/frame/multires.h"
#include "gl/resource/buffer.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/pass_state.h"
#include "gl/resource/program.h"
#include "gl/resource/query.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"
#include "gl/technique/technique.h"

namespace bounce::gl {

class MultiresGather {
public:
    static constexpr int kMaxLevels = MultiresPyramid::kMaxLevels;

    // asFragments: which form the gathers take (gatherAsFragments()).
    MultiresGather(Frame& frame, const MultiresSettings& settings, bool asFragments = defaultGatherAsFragments());

    // The whole of §3.2 with the VPL cache [0, vplCount) of `vpls` (glsl/technique/isr/vpl.glsl, binding 8).
    void run(Frame& frame, const Buffer& vpls, int vplCount, PassTimers& timers);

    // The same passes one by one, for gathers other than the VPL cache (hisr's VPL tree): the program
    // given to gather() is made by gatherProgram() from a fragment shader and a compute shader that run
    // the same sum (common/multires.glsl; the compute one through technique/isr/valid_list.glsl).
    void buildPyramid(Frame& frame, PassTimers& timers);
    // The eye-space thresholds of multiresSettingsFrom(values), applied from the next frame on.
    void setThresholds(const ParamValues& values)
    {
        pyramid_.setThresholds(float(values.get("depthThreshold")), float(values.get("normalThreshold")));
    }
    void markValidFragments(Frame& frame, PassTimers& timers);
    // Draws the stenciled quad `draws` times with additive blending (rgb), calling setupDraw(program, i)
    // before draw i: gathers are split into blocks of the VPL cache (vpl_gather.h) or ranges of top
    // patches of the VPL tree (see loopBudget()).
    // perFragment: what one fragment of one draw does (PassCost), for the pass's bound.
    // As a compute pass (gatherAsFragments() false) the valid fragments are first listed from the stencil
    // pass's marks (multires_valid_list.comp), then `program` is dispatched over the list `draws` times,
    // each invocation adding into its fragment's rgb: the same fragments get the same light.
    // invocationsPerFragment: consecutive invocations of the compute form that share one listed fragment
    // (hisr_gather.comp's lanes); the compute shader divides its index (valid_list.glsl) by it.
    void gather(Frame& frame, Program& program, PassTimers& timers, int draws = 1,
                const std::function<void(Program&, int)>& setupDraw = {}, const PassCost& perFragment = {},
                int invocationsPerFragment = 1);
    // Which form of the gather to run (preferFragmentPasses(), gl/probe/machine_probe.h: by the probe's
    // ceilings when known): the paper's stenciled quad on a software rasteriser, where fragment work is as
    // fast as compute work, and a compute pass elsewhere: a GPU may shade fragments on a small part of its
    // units (an NVIDIA H100: graphics in 2 of 66 TPCs; bounce probe read 1.8 TFLOP/s in a
    // fragment pass and 46 in a compute pass, and hisr's gather took 16.8 ms as fragments at 1024x768).
    static bool defaultGatherAsFragments();
    bool gatherAsFragments() const { return asFragments_; }
    // The parameter that chooses the form ("gather": auto|fragments|compute), and its value.
    static ParamDecl gatherFormParam();
    static bool gatherAsFragmentsFrom(const ParamValues& values, const std::vector<ParamDecl>& decls);
    void upsample(Frame& frame, PassTimers& timers);
    // [NW09]'s path, after buildPyramid(): refine() selects the valid fragments by iterative subdivision
    // (the same set, counts and neighbour marks as markValidFragments()) and keeps them as a vertex list;
    // splat() draws that list once per VPL of the cache [0, vplCount). Returns the points per VPL.
    int refine(Frame& frame, PassTimers& timers);
    void splat(Frame& frame, const Buffer& vpls, int vplCount, PassTimers& timers);
    // Loop iterations one shader invocation may run: llvmpipe silently ends every invocation after 65535
    // loop iterations in total (gallivm's loop limiter, shared by all loops of a shader), so there long
    // gathers are split over several draws; unlimited elsewhere.
    static int loopBudget();
    // The gather's program in this gather's form: the fragment shader or the compute shader.
    Program gatherProgram(const std::string& label, const std::string& fragmentPath, const std::string& computePath,
                          const std::vector<Define>& defines = {}) const;

    const MultiresSettings& settings() const { return pyramid_.settings(); }
    const MultiresPyramid& pyramid() const { return pyramid_; }
    MultiresPyramid& pyramid() { return pyramid_; }
    // Levels actually used: coarsestLevel, or fewer when one patch already covers the whole image.
    int coarsestLevel() const { return pyramid_.coarsestLevel(); }
    // Where level l lies in the flattened buffer: origin (x, y) and size (w, h) in texels.
    glm::ivec4 levelRect(int level) const { return pyramid_.levelRect(level); }
    // The flattened multiresolution illumination buffer: rgb the gathered light without the receiver's
    // diffuse colour; a 0 where no valid fragment, else 1 + the mask of the neighbours the upsampling
    // interpolates with (glsl/common/multires.glsl: sameSurfaceNeighbours).
    const Texture& illumination() const { return illumination_; }
    // Valid fragments per level of the last frame (waits for the stencil pass's occlusion queries, or
    // reads the refinement's counters back).
    std::vector<int> fragmentsPerLevel() const;
    // "fragments.level0" ... "fragments.levelN" and "fragments.total".
    std::vector<Counter> counters() const;

private:
    MultiresPyramid pyramid_;
    Texture illumination_, stencil_;
    Framebuffer fbo_;
    Buffer counts_;                      // the refinement's valid fragments per level (multires-splat)
    std::vector<Query> validQueries_;    // the stencil pass's, one GL_SAMPLES_PASSED per level
    bool countsFromQueries_ = true;      // which of the two the last frame filled
    mutable std::vector<int> lastValid_; // the counts fragmentsPerLevel() last read (the stencil pass's cost)
    VertexArray fullscreenVao_{"multires.fullscreen"};
    // Draws a full-screen triangle clipped to each level's rectangle of the flattened buffer, with the
    // level in the program's drawLevel uniform; perLevel(level) runs before the level's draw.
    void drawLevels(Program& program, PassState state, const std::function<void(int)>& perLevel = {});
    // gather()'s two forms; each returns the valid fragments the stencil pass counted.
    double gatherAsQuad(Frame& frame, Program& program, int draws, const std::function<void(Program&, int)>& setupDraw);
    double gatherAsList(Frame& frame, Program& program, int draws, const std::function<void(Program&, int)>& setupDraw,
                        int invocationsPerFragment);
    // The groups of 64 of each list dispatch: the longest list there can be, every texel valid.
    std::size_t listGroups(int invocationsPerFragment) const;
    bool asFragments_;
    Program stencilSetup_, cacheGather_; // cacheGather_: the fragment or the compute form
    // [NW09]'s path, allocated on the first refine(): work lists, counters, the splat vertices.
    Buffer workLists_[2], refineCounts_, splatVertices_;
    VertexArray splatVao_;
    Program refine_, splat_;
    int splatCount_ = 0;
    // The compute gather's list of valid fragments (a count, then x | y << 16 each), made on its first use.
    Buffer validList_;
    Program validListProgram_;

    void allocate(); // the illumination buffer and stencil, laid out as the pyramid's flattened buffer
};

} // namespace bounce::gl
