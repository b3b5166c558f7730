// bounce render: one scene, one technique, to EXR (linear radiance) + PNG (tone mapped) + JSON record.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.h"
#include "app/options.h"
#include "app/render_job.h"
#include "app/render_sequence.h"
#include "core/image.h"
#include "core/metrics.h"

namespace bounce::app {

namespace {
const char* kUsage =
    "usage: bounce render [--scene NAME|PATH] [--technique NAME] [--size WxH] [--out FILE.exr|FILE.png]\n"
    "                     [--set key=value]... [--frames N] [--warmup N] [--json FILE]\n"
    "                     [--backend egl|osmesa|glfw] [--exposure STOPS] [--reference FILE.exr]\n"
    "                     [--camera POS:TARGET[:FOV]] [--light TYPE:key=value;...]... [--indirect-scale N]\n"
    "       bounce render --path FILE.json [--scene S] [--technique T] [--size WxH] [--out DIR]\n"
    "                     [--every K] [--indirect-scale N] [--set key=value]... [--backend B]\n"
    "\n"
    "Renders the scene with the technique and writes FILE.exr (linear radiance), FILE.png (tone mapped,\n"
    "sRGB) and FILE.json (backend, GL renderer, parameters, per-pass GPU ms: median over the timed\n"
    "frames after the warm-up frames, counters, bytes per GL resource). Files are written atomically.\n"
    "\n"
    "  --scene      built-in name (see `bounce list`), a .gltf/.glb path or a scene setup\n"
    "               (.json, e.g. assets/setups/sponza-sun.json)              [cornell-spot]\n"
    "  --technique  see `bounce list`                                        [direct]\n"
    "  --size       image size                                                [512x512]\n"
    "  --out        output image; its sibling .exr/.png/.json are written too [out/render.exr]\n"
    "  --set        a technique or frame parameter, e.g. --set shadow.pcf=0 (repeatable)\n"
    "  --frames     timed frames (median reported); for a progressive technique\n"
    "               (`bounce list`) the accumulation steps, started after warm-up [10]\n"
    "               The view is still: the frames after the first each sample pixels, shadow\n"
    "               maps and area lights anew, and the image is their mean, which converges\n"
    "               to the path tracer's box-filtered pixels (--set accumulate=0: the last\n"
    "               frame alone)\n"
    "  --warmup     untimed frames before them                               [2]\n"
    "  --json       where the JSON record goes                               [next to --out]\n"
    "  --backend    egl (headless, GPU when present), osmesa, glfw (window)   [egl]\n"
    "  --exposure   PNG exposure in stops                                    [0]\n"
    "  --reference  an EXR (e.g. from `bounce reference`) of the same size or one that divides it: the\n"
    "               record gets the relative RMSE against it, after every step for a progressive\n"
    "               technique (error against time, for plotting)\n";
} // namespace

int cmdRender(const Args& args)
{
    const std::string usage = std::string(kUsage) + kSequenceOptionsHelp + kSceneOptionsHelp;
    const Options o(args,
                    {{"scene"},
                     {"technique"},
                     {"size"},
                     {"out"},
                     {"set", true, true},
                     {"frames"},
                     {"warmup"},
                     {"json"},
                     {"backend"},
                     {"exposure"},
                     {"reference"},
                     {"camera"},
                     {"light", true, true},
                     {"path"},
                     {"every"},
                     {"indirect-scale"}},
                    usage);
    if (o.helpRequested()) {
        std::fputs(usage.c_str(), stdout);
        return 0;
    }
    if (!o.positional().empty()) throw UsageError("unexpected argument '" + o.positional()[0] + "'\n\n" + usage);
    if (o.has("path")) return renderSequence(o);
    if (o.has("every")) throw UsageError("--every needs --path (it thins a sequence's frames)");

    // Everything the user gave is checked before anything is created or written.
    int width = 512, height = 512;
    if (o.has("size")) parseSize(o.get("size"), width, height);
    const int frames = o.getInt("frames", 10, 1, 100000);
    const int warmup = o.getInt("warmup", 2, 0, 100000);
    const float exposure = float(o.getDouble("exposure", 0.0, -64.0, 64.0));
    const int indirectScale = o.getInt("indirect-scale", 1, 1, 16);
    const std::filesystem::path out = o.get("out", "out/render.exr");
    const std::string ext = out.extension().string();
    if (ext != ".exr" && ext != ".png") throw UsageError("--out must end in .exr or .png, not '" + out.string() + "'");
    const std::string sceneArg = o.get("scene", "cornell-spot");
    const std::string techniqueName = o.get("technique", "direct");
    CliTechnique chosen = techniqueForCli(techniqueName, o.all("set"));
    gl::ParamValues& frameValues = chosen.frameValues;
    gl::ParamValues& techniqueValues = chosen.techniqueValues;
    // Where the files go, checked before any work: a run that cannot write its results does not start.
    std::filesystem::path exr = out, png = out, json = o.get("json", "");
    exr.replace_extension(".exr");
    png.replace_extension(".png");
    if (json.empty()) json = std::filesystem::path(out).replace_extension(".json");
    try {
        for (const auto& p : {exr, png, json}) core::checkOutputPath(p.string());
    } catch (const core::ImageError& e) {
        throw UsageError(e.what());
    }
    core::Scene scene = loadSceneForCli(sceneArg);
    applySceneOptions(scene, o.get("camera"), o.all("light"));
    core::Image reference;
    if (o.has("reference")) {
        try {
            reference = core::readImage(o.get("reference"));
        } catch (const std::exception& e) {
            throw UsageError("--reference: " + std::string(e.what()));
        }
        if (width % reference.width != 0 || height % reference.height != 0)
            throw UsageError("--reference is " + std::to_string(reference.width) + "x" +
                             std::to_string(reference.height) + ": its size must divide the render's " +
                             std::to_string(width) + "x" + std::to_string(height));
    }
    // The error of an image against the reference, box-downsampled to the reference's size.
    const auto errorOf = [&](const core::Image& image) {
        return core::relativeRmse(core::boxDownsample(image, reference.width, reference.height), reference);
    };

    auto context = createContextForCli(o.get("backend", "egl"), o.get("backend") == "glfw");
    std::printf("GL renderer: %s (%s, %s)\n", context->info().renderer.c_str(), context->info().platform.c_str(),
                context->info().version.c_str());

    const std::unique_ptr<gl::Renderer> made =
        makeRendererForCli(scene, techniqueName, frameValues, techniqueValues, width, height, indirectScale);
    gl::Renderer& renderer = *made;
    for (int i = 0; i < warmup; ++i) renderer.renderFrame(false);
    // A progressive technique's timed frames are its accumulation steps from a fresh start.
    const bool progressive = renderer.technique().progressive;
    if (progressive) renderer.restartAccumulation();
    nlohmann::json progress = nlohmann::json::array();
    double elapsedMs = 0.0;
    for (int i = 0; i < frames; ++i) {
        renderer.renderFrame(true);
        if (!progressive) continue;
        for (const gl::PassStat& p : renderer.timers().lastFrame()) elapsedMs += p.medianMs;
        nlohmann::json step = {{"step", i + 1}, {"accumulated", renderer.accumulatedSteps()}, {"elapsedMs", elapsedMs}};
        if (!reference.rgb.empty()) step["relativeRmse"] = errorOf(renderer.image());
        progress.push_back(step);
    }
    const core::Image image = renderer.image();

    nlohmann::json record = runRecord(context->info(), sceneArg, renderer);
    record["outputs"] = {{"exr", exr.string()}, {"png", png.string()}};
    record["indirectScale"] = indirectScale;
    if (progressive) record["progress"] = progress;
    if (!reference.rgb.empty()) {
        record["reference"] = o.get("reference");
        record["relativeRmse"] = errorOf(image);
        std::printf("relative RMSE against %s: %.4f\n", o.get("reference").c_str(),
                    record["relativeRmse"].get<double>());
    }
    // The three files appear together or not at all.
    core::FileSet files;
    files.addImage(exr.string(), image);
    files.addImage(png.string(), image, exposure);
    files.add(json.string(), recordText(record));
    try {
        files.commit();
    } catch (const core::ImageError& e) {
        throw UsageError(e.what());
    }

    std::printf("%s on %s, %dx%d, %d timed frames after %d warm-up:\n", techniqueName.c_str(), sceneArg.c_str(), width,
                height, frames, warmup);
    printPassTable(renderer, context->info().renderer);
    for (const gl::Counter& c : renderer.counters()) std::printf("  %s = %g\n", c.name.c_str(), c.value);
    for (const gl::Counter& c : renderer.frameCounters()) std::printf("  %s = %g\n", c.name.c_str(), c.value);
    std::printf("wrote %s\n      %s\n      %s\n", exr.string().c_str(), png.string().c_str(), json.string().c_str());
    // The files are kept (they show where), but a run that wrote NaN or Inf failed.
    if (const std::size_t bad = record["nonFiniteValues"].get<std::size_t>(); bad > 0) {
        std::fprintf(stderr, "bounce render: error: the image has %zu non-finite (NaN/Inf) values\n", bad);
        return 1;
    }
    return 0;
}

} // namespace bounce::app
