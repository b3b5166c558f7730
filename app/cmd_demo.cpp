// bounce demo: a window with Dear ImGui (app/demo.h). This file parses and checks the options, the
// script included, before any window or GL call, so that bad input exits with status 2 at once.
#include <cstdio>
#include <utility>

#include "app/commands.h"
#include "app/demo.h"
#include "app/demo_script.h"
#include "app/options.h"
#include "app/render_job.h"
#include "app/roofline.h"
#include "core/image.h"

namespace bounce::app {

namespace {

const std::string kUsage =
    std::string(
        "usage: bounce demo [--scene NAME|PATH] [--technique NAME] [--size WxH] [--set key=value]...\n"
        "                   [--reference FILE.exr] [--script STEPS] [--frame-log FILE.csv] [--camera "
        "POS:TARGET[:FOV]]\n"
        "                   [--light SPEC]...\n"
        "\n"
        "Opens a window. Right mouse drag looks around, W/A/S/D/Q/E move, F12 saves a screenshot\n"
        "(EXR + PNG in out/). The panel switches techniques, sets their parameters and the frame's (a frame\n"
        "parameter rebuilds both sides of a comparison), moves the light and compares: two techniques side\n"
        "by side (each half labelled with its technique, the right one with its relative RMSE against the\n"
        "left), or one against a reference EXR (heat map, relative RMSE).\n"
        "\n"
        "  --scene      built-in name or .gltf/.glb path   [cornell-spot]\n"
        "  --technique  initial technique                  [direct]\n"
        "  --size       window size                        [1024x768]\n"
        "  --reference  an EXR to compare against (same size as the render)\n"
        "  --script     comma-separated steps run in order, for automation, checked before the window opens:\n"
        "               wait:N (frames), technique:NAME, set:key=value (the left technique's parameters or the\n"
        "               frame's, e.g. set:shadow.size=512), compare:NAME (side by side),\n"
        "               screenshot:FILE.exr (also the .png; when comparing, FILE-right.exr/.png too),\n"
        "               move:N (the camera moves sideways during the next N frames; the script goes on at once,\n"
        "               so follow it with wait:N to see them), budget:MS (the frame budget), quit\n"
        "  --frame-log  a CSV of every frame, written when the demo ends: seconds since start, frame_ms (since\n"
        "               the last frame), render_ms (the renderers alone), indirect_scale (1: full resolution),\n"
        "               direct_samples (moving frames' points of the direct light), moving, technique, passes\n"
        "               (the left renderer's: name=ms;...)\n"
        "\n"
        "Frame budget (panel, 100 ms by default): while the camera or the light moves and frames take longer\n"
        "than the budget, indirect light is computed at 1/2, 1/4 or 1/8 of the resolution and upsampled\n"
        "(joint bilateral); once still for a quarter of a second it is full resolution again, and\n"
        "progressive techniques accumulate. The same technique keeps its state at every scale. Moving\n"
        "frames under a quarter of the budget at full resolution take 2, 4, then 8 points of the direct\n"
        "light per pixel instead (moving.directSamples, unless --set names it); over budget those go first.\n"
        "Temporal reuse (the frame parameters temporal and temporal.direct): moving frames blend their direct\n"
        "light, and the indirect light of a technique that draws new samples each frame, with the frames\n"
        "before, reprojected (gl/frame/README.md, \"Moving frames\"). On by default on a GPU; off on a software\n"
        "rasterizer such as llvmpipe, where at 1024x768 its passes took the moving frames of isr on cornell-spot\n"
        "from 12 to 7 frames/s. A --set of either parameter replaces the default with what it says.\n") +
    kSceneOptionsHelp;

} // namespace

int cmdDemo(const Args& args)
{
    const Options o(args,
                    {{"scene"},
                     {"technique"},
                     {"size"},
                     {"set", true, true},
                     {"reference"},
                     {"script"},
                     {"camera"},
                     {"light", true, true},
                     {"frame-log"}},
                    kUsage);
    if (o.helpRequested()) {
        std::fputs(kUsage.c_str(), stdout);
        return 0;
    }
    if (!o.positional().empty()) throw UsageError("unexpected argument '" + o.positional()[0] + "'\n\n" + kUsage);
    int width = 1024, height = 768;
    if (o.has("size")) parseSize(o.get("size"), width, height);
    DemoSettings settings;
    CliTechnique chosen = techniqueForCli(o.get("technique", "direct"), o.all("set"));
    settings.technique = chosen.info->name;
    settings.frameValues = std::move(chosen.frameValues);
    settings.techniqueValues = std::move(chosen.techniqueValues);
    settings.script = parseDemoScript(o.get("script"), settings.technique);
    if (o.has("frame-log")) {
        try {
            core::checkOutputPath(o.get("frame-log"));
        } catch (const core::ImageError& e) {
            throw UsageError(e.what());
        }
        settings.frameLog = o.get("frame-log");
    }
    if (o.has("reference")) {
        try {
            settings.reference = core::readImage(o.get("reference"));
        } catch (const core::ImageError& e) {
            throw UsageError(e.what());
        }
    }
    const std::string sceneArg = o.get("scene", "cornell-spot");
    settings.scene = loadSceneForCli(sceneArg);
    applySceneOptions(settings.scene, o.get("camera"), o.all("light"));

    gl::ContextOptions co;
    co.width = width;
    co.height = height;
    co.title = "Bounce - " + sceneArg;
    std::unique_ptr<gl::Context> context;
    try {
        context = gl::Context::create(gl::Backend::Glfw, co);
    } catch (const gl::ContextError& e) {
        throw UsageError(e.what());
    }
    gl::setKnownCeilings(cachedCeilings(context->info().renderer));
    std::printf("GL renderer: %s (%s)\n", context->info().renderer.c_str(), context->info().platform.c_str());
    std::printf("%s\n", chooseDemoTemporal(settings.frameValues, o.all("set"), gl::softwareRasterizer()).c_str());
    std::printf("%s\n", chooseDemoEdgeAA(settings.frameValues, o.all("set"), gl::softwareRasterizer()).c_str());
    for (const std::string& kv : o.all("set"))
        if (kv.substr(0, kv.find('=')) == "moving.directSamples") settings.budgetDirectSamples = false;
    Demo demo(*context, std::move(settings));
    return demo.run();
}

} // namespace bounce::app
