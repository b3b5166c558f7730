#include "app/demo_script.h"

#include <sstream>
#include <stdexcept>

#include "app/commands.h"
#include "app/render_job.h"
#include "gl/technique/technique.h"

namespace bounce::app {

namespace {

const gl::TechniqueInfo& techniqueNamed(const std::string& name, const std::string& step)
{
    try {
        return gl::findTechnique(name);
    } catch (const std::invalid_argument& e) {
        throw UsageError("--script: step '" + step + "': " + e.what());
    }
}

int waitFrames(const std::string& text, const std::string& step)
{
    std::size_t used = 0;
    long n = -1;
    try {
        n = std::stol(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (text.empty() || used != text.size() || n < 0 || n > 1000000)
        throw UsageError("--script: step '" + step + "': wait needs a number of frames in 0..1000000");
    return int(n);
}

} // namespace

bool isFrameParam(const std::string& key)
{
    for (const gl::ParamDecl& d : gl::frameParams())
        if (d.name == key) return true;
    return false;
}

std::vector<DemoStep> parseDemoScript(const std::string& text, const std::string& initialTechnique)
{
    // The technique that a set: applies to is the one selected at that point of the script, so the
    // checks follow the technique: steps. Values are checked with the same code as --set.
    const gl::TechniqueInfo* current = &techniqueNamed(initialTechnique, "--technique " + initialTechnique);
    gl::ParamValues frameValues(gl::frameParams()), techniqueValues(current->params);
    std::vector<DemoStep> steps;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        if (item.empty()) continue;
        const auto colon = item.find(':');
        DemoStep s{item.substr(0, colon), colon == std::string::npos ? "" : item.substr(colon + 1)};
        if (s.verb == "wait") {
            waitFrames(s.arg, item);
        } else if (s.verb == "technique") {
            current = &techniqueNamed(s.arg, item);
            techniqueValues = gl::ParamValues(current->params);
        } else if (s.verb == "compare") {
            techniqueNamed(s.arg, item);
        } else if (s.verb == "set") {
            try {
                applySets({s.arg}, *current, frameValues, techniqueValues);
            } catch (const UsageError& e) {
                throw UsageError("--script: step '" + item + "': " + e.what());
            }
        } else if (s.verb == "screenshot") {
            if (s.arg.empty()) throw UsageError("--script: step '" + item + "': screenshot needs a file name");
        } else if (s.verb != "quit") {
            throw UsageError("--script: unknown step '" + item +
                             "' (steps: wait:N, technique:NAME, set:key=value, compare:NAME, screenshot:FILE, quit)");
        }
        steps.push_back(s);
    }
    return steps;
}

} // namespace bounce::app
