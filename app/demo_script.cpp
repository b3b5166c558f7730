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

// The step's whole argument as an integer in [lo, hi]; `what` says what it counts ("frames").
int stepNumber(const std::string& text, const std::string& step, const std::string& verb, const char* what, long lo,
               long hi)
{
    std::size_t used = 0;
    long n = lo - 1;
    try {
        n = std::stol(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (text.empty() || used != text.size() || n < lo || n > hi)
        throw UsageError("--script: step '" + step + "': " + verb + " needs a number of " + what + " in " +
                         std::to_string(lo) + ".." + std::to_string(hi));
    return int(n);
}

} // namespace

bool isFrameParam(const std::string& key)
{
    for (const gl::ParamDecl& d : gl::frameParams())
        if (d.name == key) return true;
    return false;
}

std::string chooseDemoTemporal(gl::ParamValues& frameValues, const std::vector<std::string>& sets,
                               bool softwareRasterizer)
{
    for (const std::string& kv : sets) {
        const std::string key = kv.substr(0, kv.find('='));
        if (key == "temporal" || key == "temporal.direct") return "temporal reuse: as --set says";
    }
    if (softwareRasterizer)
        return "temporal reuse: off on a software rasterizer (its passes cost more than the moving frames' budget; "
               "--set temporal=1 --set temporal.direct=1 turns it on)";
    frameValues.setValue("temporal", 1.0);
    frameValues.setValue("temporal.direct", 1.0);
    return "temporal reuse: on (moving frames average the direct and indirect light of the frames before)";
}

std::string chooseDemoEdgeAA(gl::ParamValues& frameValues, const std::vector<std::string>& sets,
                             bool softwareRasterizer)
{
    for (const std::string& kv : sets)
        if (kv.substr(0, kv.find('=')) == "edgeAA") return "edge antialiasing: as --set says";
    if (softwareRasterizer)
        return "edge antialiasing of moving frames: off on a software rasterizer (--set edgeAA=1 turns it on)";
    frameValues.setValue("edgeAA", 1.0);
    return "edge antialiasing of moving frames: on (pixels an edge crosses take each side's light by area)";
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
            stepNumber(s.arg, item, "wait", "frames", 0, 1000000);
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
        } else if (s.verb == "move") {
            stepNumber(s.arg, item, "move", "frames", 1, 100000);
        } else if (s.verb == "budget") {
            stepNumber(s.arg, item, "budget", "milliseconds", 1, 100000);
        } else if (s.verb == "screenshot") {
            if (s.arg.empty()) throw UsageError("--script: step '" + item + "': screenshot needs a file name");
        } else if (s.verb != "quit") {
            throw UsageError("--script: unknown step '" + item +
                             "' (steps: wait:N, technique:NAME, set:key=value, compare:NAME, screenshot:FILE, move:N, "
                             "budget:MS, quit)");
        }
        steps.push_back(s);
    }
    return steps;
}

FrameBudgetState nextFrameBudget(FrameBudgetState s, bool moving, double frameMs, double budgetMs, bool scales,
                                 bool addPoints)
{
    if (!moving) {
        s.indirectScale = 1;
    } else if (frameMs > budgetMs) {
        if (addPoints && s.directSamples > 1)
            s.directSamples /= 2;
        else if (scales && s.indirectScale < 8)
            s.indirectScale *= 2;
    } else if (frameMs < 0.25 * budgetMs) {
        if (s.indirectScale > 1)
            s.indirectScale /= 2;
        else if (addPoints && s.directSamples < kBudgetMaxDirectSamples)
            s.directSamples *= 2;
    }
    if (!scales) s.indirectScale = 1;
    return s;
}

} // namespace bounce::app
