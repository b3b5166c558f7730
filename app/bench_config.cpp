#include "app/bench_config.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/options.h"
#include "app/render_job.h"
#include "core/light_paths.h"

namespace bounce::app {

namespace {

using nlohmann::json;

// Every refusal names the key as a path into the file ("runs[2].set.vpls") and what it must be.
[[noreturn]] void refuse(const std::string& key, const std::string& what)
{
    throw UsageError("bench config: " + key + ": " + what);
}

std::string typeText(const json& v)
{
    return std::string(v.type_name()) + " " + v.dump().substr(0, 40);
}

// Only these keys; an unknown one (a typo: "frame" for "frames") is refused, not ignored.
void allowOnly(const json& object, const std::string& key, std::initializer_list<const char*> allowed)
{
    if (!object.is_object()) refuse(key, "must be an object {...}, not " + typeText(object));
    for (const auto& [k, v] : object.items())
        if (std::find_if(allowed.begin(), allowed.end(), [&k](const char* a) { return k == a; }) == allowed.end()) {
            std::string list;
            for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
            refuse((key.empty() ? "" : key + ".") + k, "unknown key (allowed: " + list + ")");
        }
}

// A whole number in [lo, hi] (5.0 counts as 5).
int integer(const json& v, const std::string& key, long long lo, long long hi)
{
    if (!v.is_number() || v.is_boolean() || v.get<double>() != std::floor(v.get<double>()))
        refuse(key, "must be a whole number, not " + typeText(v));
    const double d = v.get<double>();
    if (d < double(lo) || d > double(hi))
        refuse(key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], not " + v.dump());
    return int(d);
}

std::string text(const json& v, const std::string& key)
{
    if (!v.is_string()) refuse(key, "must be a string, not " + typeText(v));
    return v.get<std::string>();
}

void size(const json& v, const std::string& key, int& width, int& height)
{
    try {
        parseSize(text(v, key), width, height);
    } catch (const UsageError&) {
        refuse(key, "must be \"WxH\" with each in 1..16384 (e.g. \"128x128\"), not " + v.dump());
    }
}

std::vector<std::string> names(const json& v, const std::string& key)
{
    if (!v.is_array() || v.empty()) refuse(key, "must be a non-empty list of names, not " + typeText(v));
    std::vector<std::string> out;
    for (std::size_t i = 0; i < v.size(); ++i) out.push_back(text(v[i], key + "[" + std::to_string(i) + "]"));
    return out;
}

// A parameter value as `--set` takes it: a number, a boolean or a string ("auto", a choice's name).
std::string valueText(const json& v, const std::string& key)
{
    if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
    if (v.is_number_integer()) return std::to_string(v.get<long long>());
    if (v.is_number()) {
        // The shortest text that reads back as the same double: 3e-4 stays 0.0003 in the labels, not
        // 0.00029999999999999997, and still round-trips exactly.
        char buf[64];
        const auto r = std::to_chars(buf, buf + sizeof buf, v.get<double>());
        return std::string(buf, r.ptr);
    }
    if (v.is_string()) return v.get<std::string>();
    refuse(key, "a parameter value must be a number, a boolean or a string, not " + typeText(v));
}

// A technique's "set": key=value texts, each checked against the technique's (and the frame's)
// declarations: name, type and range (ParamValues::set).
std::vector<std::string> sets(const json& v, const std::string& key)
{
    if (!v.is_object()) refuse(key, "must be an object {\"name\": value}, not " + typeText(v));
    std::vector<std::string> out;
    for (const auto& [k, value] : v.items()) out.push_back(k + "=" + valueText(value, key + "." + k));
    return out;
}

const gl::TechniqueInfo& technique(const json& v, const std::string& key)
{
    try {
        return gl::findTechnique(text(v, key));
    } catch (const std::invalid_argument& e) {
        refuse(key, e.what());
    }
}

// The technique takes these parameters with these values; `key` names the run's "set" or "sweep".
void checkParameters(const gl::TechniqueInfo& info, const std::vector<std::string>& settings, const std::string& key)
{
    gl::ParamValues f(gl::frameParams()), t(info.params);
    for (const std::string& s : settings) try {
            applySets({s}, info, f, t);
        } catch (const UsageError& e) {
            refuse(key + "." + s.substr(0, s.find('=')), e.what());
        }
    // The references are of the scene as loaded: a render without its normal maps would be held against
    // images with them. A setup drops them for both renderers.
    if (!f.getBool("normalMaps"))
        refuse(key + ".normalMaps",
               "the references see the scene's normal maps; to compare without them, give the run a scene setup "
               "with \"materials\": {\"*\": {\"normalTexture\": false}} (core/scene_setup.h)");
}

// A camera-path run: the file (read relative to the current folder, as `bounce render --path` reads it),
// how often frames are measured, the indirect scale and the still frames to compare with. The keys of
// still runs mean nothing along a path and are refused with it.
void pathRun(const json& run, const std::string& key, BenchSetting& s)
{
    for (const char* k : {"warmup", "frames", "curve", "temporalFrames", "against"})
        if (run.contains(k))
            refuse(key + "." + k, "cannot be given with \"path\": a camera path renders one frame per step");
    s.pathFile = text(run["path"], key + ".path");
    try {
        s.path = core::loadCameraPath(s.pathFile);
        std::ifstream in(s.pathFile);
        s.pathText = json::parse(in).dump();
    } catch (const std::exception& e) {
        refuse(key + ".path", e.what());
    }
    if (run.contains("every")) s.every = integer(run["every"], key + ".every", 1, 100000);
    if (run.contains("indirectScale")) s.indirectScale = integer(run["indirectScale"], key + ".indirectScale", 1, 16);
    if (run.contains("stillFrames")) s.stillFrames = integer(run["stillFrames"], key + ".stillFrames", 0, 100000);
}

// A run's "set" and the cartesian product of its "sweep" lists, one setting per combination.
std::vector<BenchSetting> expandRun(const json& run, const std::string& key)
{
    allowOnly(run, key,
              {"technique", "set", "sweep", "against", "temporalFrames", "size", "scenes", "warmup", "frames", "curve",
               "full", "comment", "path", "every", "indirectScale", "stillFrames"});
    if (!run.contains("technique")) refuse(key + ".technique", "missing: every run names its technique");
    const gl::TechniqueInfo& info = technique(run["technique"], key + ".technique");
    BenchSetting base;
    base.technique = info.name;
    std::vector<std::vector<std::string>> combos{{}};
    if (run.contains("set")) {
        combos[0] = sets(run["set"], key + ".set");
        checkParameters(info, combos[0], key + ".set");
    }
    if (run.contains("sweep")) {
        const json& sweep = run["sweep"];
        if (!sweep.is_object() || sweep.empty())
            refuse(key + ".sweep", "must be a non-empty object {\"name\": [values...]}, not " + typeText(sweep));
        for (const auto& [k, list] : sweep.items()) {
            const std::string where = key + ".sweep." + k;
            if (!list.is_array() || list.empty())
                refuse(where, "needs a non-empty list of values, not " + typeText(list));
            std::vector<std::vector<std::string>> next;
            for (std::size_t i = 0; i < list.size(); ++i) {
                const std::string setting = k + "=" + valueText(list[i], where + "[" + std::to_string(i) + "]");
                checkParameters(info, {setting}, key + ".sweep");
                for (const auto& c : combos) {
                    next.push_back(c);
                    next.back().push_back(setting);
                }
            }
            combos = next;
        }
    }
    if (run.contains("against")) {
        const json& a = run["against"];
        allowOnly(a, key + ".against", {"technique", "set"});
        if (!a.contains("technique")) refuse(key + ".against.technique", "missing: {\"technique\": T, \"set\": {...}}");
        const gl::TechniqueInfo& binfo = technique(a["technique"], key + ".against.technique");
        base.baseline = binfo.name;
        if (a.contains("set")) base.baselineSets = sets(a["set"], key + ".against.set");
        checkParameters(binfo, base.baselineSets, key + ".against.set");
    }
    if (run.contains("temporalFrames")) {
        base.temporalFrames = integer(run["temporalFrames"], key + ".temporalFrames", 0, 100000);
        if (base.temporalFrames == 1) refuse(key + ".temporalFrames", "must be 0 (none) or at least 2");
    }
    if (run.contains("size")) size(run["size"], key + ".size", base.width, base.height);
    if (run.contains("scenes")) base.scenes = names(run["scenes"], key + ".scenes");
    if (run.contains("warmup")) base.warmup = integer(run["warmup"], key + ".warmup", 0, 100000);
    if (run.contains("frames")) base.frames = integer(run["frames"], key + ".frames", 1, 100000);
    if (run.contains("curve")) {
        if (!run["curve"].is_boolean()) refuse(key + ".curve", "must be true or false, not " + typeText(run["curve"]));
        base.curve = run["curve"].get<bool>();
    }
    if (run.contains("full")) {
        if (!run["full"].is_boolean()) refuse(key + ".full", "must be true or false, not " + typeText(run["full"]));
        base.fullOnly = run["full"].get<bool>();
    }
    if (run.contains("path")) pathRun(run, key, base);
    for (const char* k : {"every", "indirectScale", "stillFrames"})
        if (run.contains(k) && !run.contains("path")) refuse(key + "." + k, "is a key of a camera-path run (\"path\")");
    std::vector<BenchSetting> out;
    for (const auto& c : combos) {
        out.push_back(base);
        out.back().sets = c;
    }
    return out;
}

std::vector<BenchSetting> expand(const json& runs)
{
    if (!runs.is_array() || runs.empty())
        refuse("runs", "must be a non-empty list of runs [{\"technique\": T, ...}], not " + typeText(runs));
    std::vector<BenchSetting> out;
    for (std::size_t i = 0; i < runs.size(); ++i)
        for (BenchSetting& s : expandRun(runs[i], "runs[" + std::to_string(i) + "]")) out.push_back(std::move(s));
    return out;
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

BenchConfig readBenchConfig(const std::string& path, const std::string& cacheDir, bool full)
{
    json config;
    {
        std::ifstream in(path);
        if (!in) throw UsageError("cannot read bench config '" + path + "'");
        try {
            config = json::parse(in);
        } catch (const std::exception& e) {
            throw UsageError("bench config '" + path + "' is not JSON: " + e.what());
        }
    }
    // The whole file is checked before anything runs or is written: its shape, every key, type and
    // range, the scenes, the techniques and their parameters against their declarations.
    if (!config.is_object()) refuse("the file", "must be an object {\"runs\": [...], ...}, not " + typeText(config));
    allowOnly(config, "",
              {"comment", "size", "warmup", "frames", "reference", "scenes", "fullScenes", "runs", "compareTo", "rays",
               "pathTracerSpp"});
    if (!config.contains("runs")) refuse("runs", "missing: a bench config lists its runs (an empty sweep is an error)");
    BenchConfig c;
    if (config.contains("size")) size(config["size"], "size", c.width, c.height);
    if (config.contains("warmup")) c.warmup = integer(config["warmup"], "warmup", 0, 100000);
    if (config.contains("frames")) c.frames = integer(config["frames"], "frames", 1, 100000);
    c.settings = expand(config["runs"]);
    c.sceneNames =
        config.contains("scenes") ? names(config["scenes"], "scenes") : std::vector<std::string>{"cornell-spot"};
    // The full run's extra scenes and runs are checked in every run, loaded and kept only in the full one.
    const std::vector<std::string> fullScenes =
        config.contains("fullScenes") ? names(config["fullScenes"], "fullScenes") : std::vector<std::string>{};
    std::vector<std::string> allScenes = c.sceneNames;
    allScenes.insert(allScenes.end(), fullScenes.begin(), fullScenes.end());
    if (full) c.sceneNames = allScenes;
    if (config.contains("compareTo")) {
        c.compareTo = names(config["compareTo"], "compareTo");
        for (std::size_t i = 0; i < c.compareTo.size(); ++i) try {
                core::parseLightPaths(c.compareTo[i]);
            } catch (const std::invalid_argument& e) {
                refuse("compareTo[" + std::to_string(i) + "]", e.what());
            }
    }
    if (config.contains("rays")) c.rays = integer(config["rays"], "rays", 0, 1 << 24);
    if (config.contains("pathTracerSpp")) {
        const json& l = config["pathTracerSpp"];
        if (!l.is_array()) refuse("pathTracerSpp", "must be a list of samples per pixel, not " + typeText(l));
        for (std::size_t i = 0; i < l.size(); ++i)
            c.pathTracerSpp.push_back(integer(l[i], "pathTracerSpp[" + std::to_string(i) + "]", 1, 1 << 30));
    }
    for (std::size_t i = 0; i < config["runs"].size(); ++i)
        for (const std::string& n : config["runs"][i].value("scenes", std::vector<std::string>{}))
            if (std::find(allScenes.begin(), allScenes.end(), n) == allScenes.end())
                refuse("runs[" + std::to_string(i) + "].scenes",
                       "'" + n + "' is not in the top-level \"scenes\" or \"fullScenes\"");
    for (std::size_t i = 0; i < c.sceneNames.size(); ++i) try {
            c.scenes.push_back(loadSceneForCli(c.sceneNames[i]));
        } catch (const UsageError& e) {
            refuse("scenes[" + std::to_string(i) + "]", e.what());
        }
    if (config.contains("reference")) {
        allowOnly(config["reference"], "reference", {"spp", "noise", "size"});
        const json& r = config["reference"];
        if (r.contains("spp")) integer(r["spp"], "reference.spp", 1, 1 << 30);
        if (r.contains("noise") &&
            !(r["noise"].is_number() && r["noise"].get<double>() > 0.0 && r["noise"].get<double>() < 1.0))
            refuse("reference.noise", "must be a number in (0, 1), not " + r["noise"].dump());
        if (r.contains("size")) size(r["size"], "reference.size", c.reference.width, c.reference.height);
    }
    c.reference = referenceSpecFrom(config.value("reference", json::object()), cacheDir);
    if (!full)
        c.settings.erase(
            std::remove_if(c.settings.begin(), c.settings.end(), [](const BenchSetting& s) { return s.fullOnly; }),
            c.settings.end());
    for (const BenchSetting& s : c.settings) {
        const int w = c.widthOf(s), h = c.heightOf(s);
        if ((c.reference.width > 0 && w % c.reference.width != 0) ||
            (c.reference.height > 0 && h % c.reference.height != 0))
            refuse("reference.size", std::to_string(c.reference.width) + "x" + std::to_string(c.reference.height) +
                                         " does not divide the run size " + std::to_string(w) + "x" +
                                         std::to_string(h) + " (" + s.technique + ")");
        // The reference is rendered at its own size from the same camera: another aspect ratio sees
        // another field of view, and its pixels would be compared with stretched blocks of the render.
        if (c.reference.width > 0 && c.reference.height > 0 && w / c.reference.width != h / c.reference.height)
            refuse("reference.size", std::to_string(c.reference.width) + "x" + std::to_string(c.reference.height) +
                                         " is not the run size " + std::to_string(w) + "x" + std::to_string(h) + " (" +
                                         s.technique + ") reduced by one factor: another aspect ratio");
    }
    return c;
}

} // namespace bounce::app
