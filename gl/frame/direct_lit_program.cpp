#include "gl/frame/direct_lit_program.h"

#include <algorithm>
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
        // The program's own defines may hold one of the estimator's already (ALPHA_MASK, from the ray
        // caster's): each once.
        for (const Define& l : frame.directLightDefines(still))
            if (std::none_of(d.begin(), d.end(), [&](const Define& o) { return o.name == l.name; })) d.push_back(l);
        program = Program::compute(still ? label_ + ".still" : label_, path_, d);
    }
    frame.setDirectLightUniforms(program);
    return program;
}

} // namespace bounce::gl
