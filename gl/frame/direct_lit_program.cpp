#include "gl/frame/direct_lit_program.h"

#include <utility>

#include "gl/frame/frame.h"

namespace bounce::gl {

DirectLitProgram::DirectLitProgram(std::string label, std::string path, std::vector<Define> defines)
    : label_(std::move(label)), path_(std::move(path)), defines_(std::move(defines))
{}

Program& DirectLitProgram::forFrame(const Frame& frame)
{
    const bool still = frame.directLightStill();
    Program& program = forms_[still ? 1 : 0];
    if (!program) {
        std::vector<Define> d = defines_;
        const std::vector<Define> light = frame.directLightDefines(still);
        d.insert(d.end(), light.begin(), light.end());
        program = Program::compute(still ? label_ + ".still" : label_, path_, d);
    }
    frame.setDirectLightUniforms(program);
    return program;
}

} // namespace bounce::gl
