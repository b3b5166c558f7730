#include "app/render_job.h"

#include <cstdio>
#include <ctime>

#include "app/commands.h"
#include "core/cornell.h"
#include "core/gltf_io.h"
#include "gl/resource/allocations.h"

namespace bounce::app {

core::Scene loadSceneForCli(const std::string& nameOrPath)
{
    try {
        return core::loadScene(nameOrPath);
    } catch (const core::SceneError& e) {
        throw UsageError(e.what());
    }
}

void applySets(const std::vector<std::string>& sets, const gl::TechniqueInfo& technique, gl::ParamValues& frameValues,
               gl::ParamValues& techniqueValues)
{
    for (const std::string& s : sets) {
        const auto eq = s.find('=');
        if (eq == std::string::npos || eq == 0)
            throw UsageError("--set needs key=value, not '" + s + "' (see `bounce list` for the parameters)");
        const std::string key = s.substr(0, eq), value = s.substr(eq + 1);
        bool isFrame = false;
        for (const gl::ParamDecl& d : gl::frameParams()) isFrame |= d.name == key;
        try {
            if (isFrame) frameValues.set(gl::frameParams(), key, value);
            else techniqueValues.set(technique.params, key, value);
        } catch (const std::invalid_argument& e) {
            throw UsageError(std::string(e.what()) + (isFrame ? "" : " (technique '" + technique.name + "')"));
        }
    }
}

std::unique_ptr<gl::Context> createContextForCli(const std::string& backend, bool window)
{
    gl::Backend b;
    try {
        b = gl::parseBackend(backend);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    gl::ContextOptions o;
    o.visible = window;
    try {
        return gl::Context::create(b, o);
    } catch (const gl::ContextError& e) {
        throw UsageError(e.what());
    }
}

nlohmann::json runRecord(const gl::ContextInfo& ctx, const std::string& scene, gl::Renderer& r)
{
    nlohmann::json j;
    j["backend"] = ctx.backend;
    j["platform"] = ctx.platform;
    j["renderer"] = ctx.renderer;
    j["vendor"] = ctx.vendor;
    j["glVersion"] = ctx.version;
    j["scene"] = scene;
    j["width"] = r.frame().width();
    j["height"] = r.frame().height();
    j["technique"] = r.technique().name;
    j["lightPaths"] = core::lightPathsName(r.technique().lightPaths);
    j["parameters"] = r.techniqueValues().toJson(r.technique().params);
    j["frameParameters"] = r.frameValues().toJson(gl::frameParams());
    double total = 0.0;
    nlohmann::json passes = nlohmann::json::array();
    for (const gl::PassStat& p : r.timers().stats()) {
        passes.push_back({{"pass", p.pass}, {"medianMs", p.medianMs}, {"minMs", p.minMs}, {"maxMs", p.maxMs},
                          {"frames", p.frames}});
        total += p.medianMs;
    }
    j["passes"] = passes;
    j["totalMs"] = total;
    nlohmann::json counters = nlohmann::json::object();
    for (const gl::Counter& c : r.counters()) counters[c.name] = c.value;
    j["counters"] = counters;
    j["bytesAllocated"] = gl::Allocations::instance().byLabel();
    j["bytesAllocatedTotal"] = gl::Allocations::instance().totalBytes();
    j["time"] = std::time(nullptr);
    return j;
}

void printPassTable(gl::Renderer& r)
{
    double total = 0.0;
    std::printf("%-22s %10s %10s %10s\n", "pass", "median ms", "min ms", "max ms");
    for (const gl::PassStat& p : r.timers().stats()) {
        std::printf("%-22s %10.3f %10.3f %10.3f\n", p.pass.c_str(), p.medianMs, p.minMs, p.maxMs);
        total += p.medianMs;
    }
    std::printf("%-22s %10.3f\n", "total", total);
}

} // namespace bounce::app
