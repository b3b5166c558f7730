#include "app/render_job.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <stdexcept>

#include "app/commands.h"
#include "app/roofline.h"
#include "core/cornell.h"
#include "core/gltf_io.h"
#include "core/scene_setup.h"
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

const char* const kSceneOptionsHelp =
    "  --camera     POSITION:TARGET[:FOV_DEGREES] in metres, e.g. --camera 0.278,0.273,-0.8:0.278,0.273,0:39.3\n"
    "  --light      TYPE:key=value;... (repeatable), the project's units:\n"
    "                 point:position=X,Y,Z;intensity=W_PER_SR (one value or R,G,B)\n"
    "                 spot:position=..;direction=..|target=..;intensity=W_PER_SR;outerDeg=45;innerDeg=0\n"
    "                 directional:direction=X,Y,Z;irradiance=W_PER_M2\n"
    "                 area:corner=..;edge1=..;edge2=..;radiance=W_PER_M2_SR (emits along edge1 x edge2)\n"
    "               e.g. --light 'directional:direction=0.3,-1,0.2;irradiance=20'\n";

void applySceneOptions(core::Scene& scene, const std::string& camera, const std::vector<std::string>& lights)
{
    try {
        if (!camera.empty()) {
            core::setCameraFromJson(scene, core::cameraJsonFromArgument(camera), "--camera");
            scene.cameraSource = "command line";
        }
        for (const std::string& l : lights)
            core::addLightFromJson(scene, core::lightJsonFromArgument(l), "--light '" + l + "'");
    } catch (const core::SceneError& e) {
        throw UsageError(e.what());
    }
    if (const std::string err = scene.validate(); !err.empty()) throw UsageError("invalid scene: " + err);
    if (scene.cameraSource != "built-in") std::printf("camera: %s\n", scene.cameraSource.c_str());
    if (scene.lights.empty() && !scene.hasEmission())
        std::fprintf(stderr, "warning: the scene has no light and no emitter: the image will be black. Give --light "
                             "(see --help) or use a scene setup (assets/setups/)\n");
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
            if (isFrame)
                frameValues.set(gl::frameParams(), key, value);
            else
                techniqueValues.set(technique.params, key, value);
        } catch (const std::invalid_argument& e) {
            throw UsageError(std::string(e.what()) + (isFrame ? "" : " (technique '" + technique.name + "')"));
        }
    }
}

CliTechnique techniqueForCli(const std::string& name, const std::vector<std::string>& sets)
{
    CliTechnique t;
    try {
        t.info = &gl::findTechnique(name);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    t.frameValues = gl::ParamValues(gl::frameParams());
    t.techniqueValues = gl::ParamValues(t.info->params);
    applySets(sets, *t.info, t.frameValues, t.techniqueValues);
    return t;
}

std::unique_ptr<gl::Renderer> makeRendererForCli(const core::Scene& scene, const std::string& technique,
                                                 const gl::ParamValues& frameValues,
                                                 const gl::ParamValues& techniqueValues, int width, int height,
                                                 int indirectScale)
{
    std::unique_ptr<gl::Renderer> renderer;
    try {
        renderer = std::make_unique<gl::Renderer>(scene, technique, frameValues, techniqueValues, width, height);
    } catch (const std::invalid_argument& e) {
        throw UsageError(technique + ": " + e.what());
    }
    if (indirectScale != 1) renderer->setIndirectScale(indirectScale);
    return renderer;
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
        std::unique_ptr<gl::Context> context = gl::Context::create(b, o);
        // Passes written in two forms choose by this renderer's ceilings where `bounce probe` measured them.
        gl::setKnownCeilings(cachedCeilings(context->info().renderer));
        return context;
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
    j["cameraSource"] = r.frame().scene().cameraSource;
    j["width"] = r.frame().width();
    j["height"] = r.frame().height();
    j["technique"] = r.technique().name;
    j["lightPaths"] = core::lightPathsName(r.technique().lightPaths);
    j["parameters"] = r.techniqueValues().toJson(r.technique().params);
    j["frameParameters"] = r.frameValues().toJson(gl::frameParams());
    double total = 0.0;
    nlohmann::json passes = nlohmann::json::array();
    // Bounds when `bounce probe` has measured this renderer's ceilings (app/roofline.h).
    const std::optional<gl::Ceilings> ceilings = cachedCeilings(ctx.renderer);
    for (const gl::PassStat& p : r.timers().stats()) {
        nlohmann::json pass = {
            {"pass", p.pass}, {"medianMs", p.medianMs}, {"minMs", p.minMs}, {"maxMs", p.maxMs}, {"frames", p.frames}};
        pass.update(passWorkJson(p, ceilings ? &*ceilings : nullptr));
        passes.push_back(pass);
        total += p.medianMs;
    }
    j["passes"] = passes;
    if (ceilings) j["ceilings"] = ceilings->toJson();
    j["totalMs"] = total;
    // The image is the mean of the still frames since the view was last changed (every frame, or the timed
    // ones after a progressive technique's restart): its GPU time is theirs, what speed against error plots.
    j["imageFrames"] = r.stillFrames() + 1;
    j["imageMs"] = total * double(r.stillFrames() + 1);
    nlohmann::json counters = nlohmann::json::object();
    for (const gl::Counter& c : r.counters()) counters[c.name] = c.value;
    j["counters"] = counters;
    nlohmann::json frameCounters = nlohmann::json::object();
    for (const gl::Counter& c : r.frameCounters()) frameCounters[c.name] = c.value;
    j["frameCounters"] = frameCounters;
    if (const nlohmann::json notes = r.notes(); !notes.is_null() && !notes.empty()) j["notes"] = notes;
    j["bytesAllocated"] = gl::Allocations::instance().byLabel();
    j["bytesAllocatedTotal"] = gl::Allocations::instance().totalBytes();
    j["nonFiniteValues"] = nonFiniteValues(r.image());
    j["time"] = std::time(nullptr);
    return j;
}

std::size_t nonFiniteValues(const core::Image& image)
{
    return std::size_t(std::count_if(image.rgb.begin(), image.rgb.end(), [](float v) { return !std::isfinite(v); }));
}

namespace {

nlohmann::json withoutInfinities(const nlohmann::json& j)
{
    if (j.is_number_float() && !std::isfinite(j.get<double>())) {
        const double v = j.get<double>();
        return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v > 0 ? "inf" : "-inf");
    }
    if (j.is_object()) {
        nlohmann::json out = nlohmann::json::object();
        for (const auto& [k, v] : j.items()) out[k] = withoutInfinities(v);
        return out;
    }
    if (j.is_array()) {
        nlohmann::json out = nlohmann::json::array();
        for (const auto& v : j) out.push_back(withoutInfinities(v));
        return out;
    }
    return j;
}

} // namespace

std::string recordText(const nlohmann::json& record)
{
    return withoutInfinities(record).dump(2) + "\n";
}

void printPassTable(gl::Renderer& r, const std::string& renderer)
{
    double total = 0.0;
    const std::optional<gl::Ceilings> ceilings = cachedCeilings(renderer);
    std::printf("%-22s %10s %10s %10s", "pass", "median ms", "min ms", "max ms");
    if (ceilings) std::printf(" %10s %10s  %s", "bound ms", "efficiency", "limit");
    std::printf("\n");
    for (const gl::PassStat& p : r.timers().stats()) {
        std::printf("%-22s %10.3f %10.3f %10.3f", p.pass.c_str(), p.medianMs, p.minMs, p.maxMs);
        if (ceilings) {
            if (const auto b = passBound(p, *ceilings))
                std::printf(" %10.3f %10.3f  %s", b->boundMs, b->efficiency, b->limiter.c_str());
            else
                std::printf(" %10s %10s", "-", "-");
        }
        std::printf("\n");
        total += p.medianMs;
    }
    std::printf("%-22s %10.3f\n", "total", total);
    if (!ceilings) std::printf("(`bounce probe` measures this machine's ceilings: then each pass shows its bound)\n");
}

} // namespace bounce::app
