// bounce list: scenes, techniques and their parameters (defaults and ranges), frame parameters.
#include <cstdio>

#include "app/commands.h"
#include "app/options.h"
#include "core/cornell.h"
#include "gl/technique/technique.h"

namespace bounce::app {

namespace {
const char* kUsage = "usage: bounce list\n\nLists the built-in scenes, the techniques with their parameters, and the\n"
                     "frame parameters every technique shares (set any with --set key=value).\n";

void printParams(const std::vector<gl::ParamDecl>& params)
{
    for (const gl::ParamDecl& p : params) {
        const char* type = p.type == gl::ParamType::Int ? "int" : p.type == gl::ParamType::Bool ? "bool" : "float";
        std::printf("    %-22s %-5s default %-8g range [%g, %g]  %s\n", p.name.c_str(), type, p.defaultValue, p.min,
                    p.max, p.meaning.c_str());
    }
}
} // namespace

int cmdList(const Args& args)
{
    const Options o(args, {}, kUsage);
    if (o.helpRequested()) { std::fputs(kUsage, stdout); return 0; }
    if (!o.positional().empty()) throw UsageError("unexpected argument '" + o.positional()[0] + "'\n\n" + kUsage);
    std::printf("scenes (or any .gltf/.glb path):\n");
    for (const std::string& s : core::builtinSceneNames()) std::printf("  %s\n", s.c_str());
    std::printf("\ntechniques:\n");
    for (const gl::TechniqueInfo& t : gl::techniques()) {
        std::printf("  %-16s %s\n    paper: %s; light paths: %s\n", t.name.c_str(), t.summary.c_str(), t.paper.c_str(),
                    t.lightPaths.c_str());
        printParams(t.params);
    }
    std::printf("\nframe parameters (every technique):\n");
    printParams(gl::frameParams());
    return 0;
}

} // namespace bounce::app
