// The demo's --script: comma-separated steps that drive the window without a person (the tests run it
// under Xvfb). Parsed and checked here, with no GL and no window, so that a bad technique name, an
// unknown parameter or a bad value exits with status 2 before the window opens.
#pragma once

#include <string>
#include <vector>

#include "gl/frame/params.h"

namespace bounce::app {

struct DemoStep {
    std::string verb; // wait, technique, set, compare, screenshot, move, budget, quit
    std::string arg;  // what follows the colon ("" when none)
};

// Parses the steps and checks each against the registry: technique: and compare: name a registered
// technique, set:key=value names a frame parameter or a parameter of the technique selected at that
// point of the script (starting from `initialTechnique`) with a value in its range, wait:N has
// 0 <= N <= 1000000, screenshot: names a file, move:N (the camera moves sideways for N frames, as a held
// key would) has 1 <= N <= 100000, budget:MS (the frame budget, gl::Renderer::setIndirectScale) has
// 1 <= MS <= 100000. Throws UsageError saying which step is wrong and why.
std::vector<DemoStep> parseDemoScript(const std::string& text, const std::string& initialTechnique);

// Whether `key` is one of gl::frameParams() (changing it rebuilds the frame, so every renderer).
bool isFrameParam(const std::string& key);

// The demo's default for temporal reuse: on (the frame parameters `temporal` and `temporal.direct` set in
// `frameValues`) on a hardware renderer, off on a software rasterizer, where its passes cost more than the
// frame budget buys back (the README's paragraph on the demo's frame budget); `sets` (the command line's key=value) naming either
// parameter leaves both as they are. Returns the line the demo prints to say which and why.
std::string chooseDemoTemporal(gl::ParamValues& frameValues, const std::vector<std::string>& sets,
                               bool softwareRasterizer);
// The same for the moving frames' edge antialiasing (frame parameter `edgeAA`, gl/frame/edge_antialias.h):
// on on a hardware renderer, off on a software rasterizer (at 1024x768 on llvmpipe its two passes took
// 21 ms of isr's moving frame on cornell-spot, 320 ms in all), unless `sets` names it.
std::string chooseDemoEdgeAA(gl::ParamValues& frameValues, const std::vector<std::string>& sets,
                             bool softwareRasterizer);

// The frame budget's two settings for moving frames: the indirect light's scale (gl::Renderer::
// setIndirectScale: 1, 2, 4, 8) and the direct light's points per pixel (frame parameter
// moving.directSamples: 1, 2, 4, 8; gl/frame/README.md, "Moving frames").
struct FrameBudgetState {
    int indirectScale = 1;
    int directSamples = 1;
};
inline constexpr int kBudgetMaxDirectSamples = 8; // the Sponza walk with reuse: 6.9% at 8, 9.3% at 1, 3.5% still

// One step of the demo's frame budget after a frame of `frameMs` against `budgetMs`. Still (not
// `moving`): full resolution, the points left as they are (still frames take still.directSamples). Moving
// and over budget: first the points the budget added go (halved down to 1), then the indirect light
// coarsens (doubling its scale up to 8, where `scales`: a technique that a coarser scale does not speed up
// stays at 1). Moving and under a quarter of the budget: the other way, the indirect light back to full
// resolution first, then more points of the direct light (doubling up to kBudgetMaxDirectSamples, where
// `addPoints`: the command line did not set moving.directSamples). Doubling from under a quarter stays
// under half the budget, so the two directions do not alternate.
FrameBudgetState nextFrameBudget(FrameBudgetState state, bool moving, double frameMs, double budgetMs, bool scales,
                                 bool addPoints);

} // namespace bounce::app
