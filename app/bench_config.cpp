#include "app/bench_config.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/options.h"
#include "app/render_job.h"

namespace bounce::app {

namespace {

std::string numberText(const nlohmann::json& v)
{
    if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
    if (v.is_number_integer()) return std::to_string(v.get<long long>());
    if (v.is_number()) {
        std::ostringstream s;
        s << v.get<double>();
        return s.str();
    }
    if (v.is_string()) return v.get<std::string>();
    throw UsageError("bench config: parameter values must be numbers, booleans or strings, not " + v.dump());
}

// A run's "set" and the cartesian product of its "sweep" lists, one setting per combination.
std::vector<BenchSetting> expand(const nlohmann::json& runs)
{
    std::vector<BenchSetting> out;
    for (const auto& run : runs) {
        if (!run.contains("technique") || !run["technique"].is_string())
            throw UsageError("bench config: every run needs a \"technique\" string: " + run.dump());
        std::vector<std::vector<std::string>> combos{{}};
        if (run.contains("set"))
            for (const auto& [k, v] : run["set"].items()) combos[0].push_back(k + "=" + numberText(v));
        if (run.contains("sweep"))
            for (const auto& [k, list] : run["sweep"].items()) {
                if (!list.is_array() || list.empty())
                    throw UsageError("bench config: sweep \"" + k + "\" needs a non-empty list");
                std::vector<std::vector<std::string>> next;
                for (const auto& c : combos)
                    for (const auto& v : list) {
                        auto n = c;
                        n.push_back(k + "=" + numberText(v));
                        next.push_back(n);
                    }
                combos = next;
            }
        std::string baseline;
        std::vector<std::string> baselineSets;
        if (run.contains("against")) {
            const auto& a = run["against"];
            if (!a.is_object() || !a.contains("technique"))
                throw UsageError("bench config: \"against\" needs {\"technique\": T, \"set\": {...}}");
            baseline = a["technique"].get<std::string>();
            if (a.contains("set"))
                for (const auto& [k, v] : a["set"].items()) baselineSets.push_back(k + "=" + numberText(v));
        }
        const int temporal = run.value("temporalFrames", 0);
        if (temporal < 0 || temporal == 1) throw UsageError("bench config: temporalFrames must be 0 or >= 2");
        int width = 0, height = 0;
        if (run.contains("size")) parseSize(run["size"].get<std::string>(), width, height);
        const auto scenes = run.value("scenes", std::vector<std::string>{});
        const int warmup = run.value("warmup", -1), frames = run.value("frames", -1);
        if (warmup < -1 || frames == 0 || frames < -1)
            throw UsageError("bench config: a run's warmup >= 0 and frames >= 1");
        const bool curve = run.value("curve", false);
        for (const auto& c : combos)
            out.push_back({run["technique"].get<std::string>(), c, baseline, baselineSets, temporal, width, height,
                           scenes, warmup, frames, curve});
    }
    return out;
}

// The technique exists and takes these parameters with these values.
void checkTechnique(const std::string& name, const std::vector<std::string>& sets)
{
    const gl::TechniqueInfo* info = nullptr;
    try {
        info = &gl::findTechnique(name);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    gl::ParamValues f(gl::frameParams()), t(info->params);
    applySets(sets, *info, f, t);
}

} // namespace

bool BenchSetting::runsOn(const std::string& scene) const
{
    return scenes.empty() || std::find(scenes.begin(), scenes.end(), scene) != scenes.end();
}

std::string settingsText(const std::vector<std::string>& sets)
{
    std::string s;
    for (const auto& x : sets) s += (s.empty() ? "" : " ") + x;
    return s.empty() ? "defaults" : s;
}

BenchConfig readBenchConfig(const std::string& path, const std::string& cacheDir)
{
    nlohmann::json config;
    {
        std::ifstream in(path);
        if (!in) throw UsageError("cannot read bench config '" + path + "'");
        try {
            config = nlohmann::json::parse(in);
        } catch (const std::exception& e) {
            throw UsageError("bench config '" + path + "': " + e.what());
        }
    }
    BenchConfig c;
    parseSize(config.value("size", std::string("128x128")), c.width, c.height);
    c.warmup = config.value("warmup", 2);
    c.frames = config.value("frames", 5);
    if (c.warmup < 0 || c.frames < 1) throw UsageError("bench config: warmup >= 0 and frames >= 1");
    c.settings = expand(config.value("runs", nlohmann::json::array()));
    c.sceneNames = config.value("scenes", std::vector<std::string>{"cornell-spot"});
    c.compareTo = config.value("compareTo", std::vector<std::string>{});
    c.rays = config.value("rays", 0);
    c.pathTracerSpp = config.value("pathTracerSpp", std::vector<int>{});
    for (int spp : c.pathTracerSpp)
        if (spp < 1) throw UsageError("bench config: \"pathTracerSpp\" needs positive sample counts");
    if (c.rays < 0 || c.rays > (1 << 24)) throw UsageError("bench config: \"rays\" must be in [0, 16777216]");
    for (const BenchSetting& s : c.settings)
        for (const std::string& n : s.scenes)
            if (std::find(c.sceneNames.begin(), c.sceneNames.end(), n) == c.sceneNames.end())
                throw UsageError("bench config: a run names scene '" + n + "', which is not in \"scenes\"");
    for (const BenchSetting& s : c.settings) {
        checkTechnique(s.technique, s.sets);
        if (!s.baseline.empty()) checkTechnique(s.baseline, s.baselineSets);
    }
    for (const auto& n : c.sceneNames) c.scenes.push_back(loadSceneForCli(n));
    c.reference = referenceSpecFrom(config.value("reference", nlohmann::json::object()), cacheDir);
    for (const BenchSetting& s : c.settings) {
        const int w = c.widthOf(s), h = c.heightOf(s);
        if ((c.reference.width > 0 && w % c.reference.width != 0) ||
            (c.reference.height > 0 && h % c.reference.height != 0))
            throw UsageError("bench config: the reference size " + std::to_string(c.reference.width) + "x" +
                             std::to_string(c.reference.height) + " does not divide the run size " + std::to_string(w) +
                             "x" + std::to_string(h) + " (" + s.technique + ")");
    }
    return c;
}

} // namespace bounce::app
