// A compute program that lights points with the frame's direct light (glsl/common/lighting.glsl,
// addDirectLight): compiled in the estimator's form each frame runs (Frame::directLightStill), the still or
// the moving one, at the first frame that runs it, so that its hits get the light the frame's pixels get.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "gl/resource/program.h"

namespace bounce::gl {

class Frame;

class DirectLitProgram {
public:
    DirectLitProgram() = default;
    // `defines`: the program's own; Frame::directLightDefines are added per form.
    DirectLitProgram(std::string label, std::string path, std::vector<Define> defines);

    // The program in this frame's form, with Frame::setDirectLightUniforms applied.
    Program& forFrame(const Frame& frame);
    explicit operator bool() const { return !path_.empty(); }

private:
    std::string label_, path_;
    std::vector<Define> defines_;
    std::array<Program, 2> forms_; // moving, still
};

} // namespace bounce::gl
