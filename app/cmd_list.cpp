// bounce list: scenes, techniques and their parameters (defaults and ranges), frame parameters.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "app/commands.h"
#include "app/options.h"
#include "core/cornell.h"
#include "gl/technique/technique.h"

namespace bounce::app {

namespace {
const char* kUsage =
    "usage: bounce list [--json]\n"
    "\n"
    "Lists the built-in scenes, the techniques with their parameters, and the frame parameters every\n"
    "technique shares (set any with --set key=value).\n"
    "\n"
    "  --json   the whole registry as JSON on stdout, for scripts: scenes, light-path sets, techniques\n"
    "           (paper, light paths, passes, G-buffer channels read, progressive, parameters with type,\n"
    "           default, range or choices, meaning, and whether a change rebuilds or sets a uniform),\n"
    "           the frame's passes and parameters\n";

void printParams(const std::vector<gl::ParamDecl>& params)
{
    for (const gl::ParamDecl& p : params) {
        std::string range;
        if (p.type == gl::ParamType::Choice) {
            for (const std::string& c : p.choices) range += (range.empty() ? "" : "|") + c;
        } else if (p.type != gl::ParamType::Bool) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "[%.10g, %.10g]", p.min, p.max);
            range = buf;
            if (p.allowAuto) range += " or auto";
        }
        std::printf("    %-22s %-6s default %-8s %-18s %s%s\n", p.name.c_str(), p.typeName().c_str(),
                    p.text(p.defaultValue).c_str(), range.c_str(), p.meaning.c_str(),
                    p.update == gl::ParamUpdate::Uniform ? " (uniform)" : "");
    }
}

// The setups shipped in assets/setups/, and whether the glTF each names is there.
std::vector<std::pair<std::string, bool>> sceneSetups()
{
    namespace fs = std::filesystem;
    std::vector<std::pair<std::string, bool>> setups;
    const fs::path dir = fs::path(BOUNCE_SOURCE_ROOT) / "assets" / "setups";
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        if (e.path().extension() != ".json") continue;
        bool present = true;
        try {
            const nlohmann::json j = nlohmann::json::parse(std::ifstream(e.path()));
            if (j.contains("gltf")) present = fs::exists(dir / j["gltf"].get<std::string>());
        } catch (const std::exception&) {
            present = false;
        }
        setups.emplace_back(fs::relative(e.path(), BOUNCE_SOURCE_ROOT).string(), present);
    }
    std::sort(setups.begin(), setups.end());
    return setups;
}

nlohmann::json registryJson()
{
    nlohmann::json j;
    j["scenes"] = core::builtinSceneNames();
    j["setups"] = nlohmann::json::array();
    for (const auto& [path, present] : sceneSetups())
        j["setups"].push_back({{"path", path}, {"assetPresent", present}});
    j["lightPaths"] = core::lightPathsNames();
    j["techniques"] = nlohmann::json::array();
    for (const gl::TechniqueInfo& t : gl::techniques()) j["techniques"].push_back(t.toJson());
    nlohmann::json frame;
    frame["passes"] = nlohmann::json::array();
    for (const gl::PassDecl& p : gl::framePasses())
        frame["passes"].push_back({{"name", p.name}, {"meaning", p.meaning}});
    frame["parameters"] = nlohmann::json::array();
    for (const gl::ParamDecl& p : gl::frameParams()) frame["parameters"].push_back(p.toJson());
    j["frame"] = frame;
    return j;
}
} // namespace

int cmdList(const Args& args)
{
    const Options o(args, {{"json", false}}, kUsage);
    if (o.helpRequested()) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (!o.positional().empty()) throw UsageError("unexpected argument '" + o.positional()[0] + "'\n\n" + kUsage);
    if (o.has("json")) {
        std::printf("%s\n", registryJson().dump(2).c_str());
        return 0;
    }
    std::printf("scenes (or any .gltf/.glb path):\n");
    for (const std::string& s : core::builtinSceneNames()) std::printf("  %s\n", s.c_str());
    std::printf("\nscene setups (--scene PATH.json; the benchmark assets live in ../shared/assets):\n");
    for (const auto& [path, present] : sceneSetups())
        std::printf("  %-40s %s\n", path.c_str(), present ? "" : "(its asset is not there)");
    std::printf("\ntechniques:\n");
    for (const gl::TechniqueInfo& t : gl::techniques()) {
        std::printf("  %-16s %s\n    paper: %s; light paths: %s\n", t.name.c_str(), t.summary.c_str(), t.paper.c_str(),
                    core::lightPathsName(t.lightPaths).c_str());
        std::string passes, reads;
        for (const gl::PassDecl& p : t.passes) passes += (passes.empty() ? "" : ", ") + p.name;
        for (gl::GBufferChannel c : t.reads) reads += (reads.empty() ? "" : ", ") + gl::gbufferChannelName(c);
        std::printf("    passes: %s; reads: %s%s\n", passes.empty() ? "none" : passes.c_str(),
                    reads.empty() ? "nothing" : reads.c_str(), t.progressive ? "; progressive" : "");
        printParams(t.params);
    }
    std::printf("\nframe parameters (every technique):\n");
    printParams(gl::frameParams());
    return 0;
}

} // namespace bounce::app
