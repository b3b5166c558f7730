#include "app/render_sequence.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.h"
#include "app/render_job.h"
#include "core/camera_path.h"
#include "core/image.h"
#include "core/progress.h"

namespace bounce::app {

namespace fs = std::filesystem;

const char* const kSequenceOptionsHelp =
    "  --path       a camera path (FILE.json, e.g. bench/paths/cornell-orbit.json): renders its frames\n"
    "               0..N-1, one renderer frame per step and no warm-up, the camera and the punctual\n"
    "               lights of each step from the path:\n"
    "                 {\"frames\": N, \"keys\": [{\"frame\": F, \"camera\": \"POS:TARGET:FOV\"}, ...],\n"
    "                  \"lights\": [{\"frame\": F, \"light\": [\"SPEC\", ...]}, ...]}\n"
    "               camera and light specs as --camera and --light take them (every key gives the field\n"
    "               of view; point, spot and directional lights; key frames strictly increase and lie\n"
    "               in 0..N-1); position, target and field of view interpolate linearly between keys\n"
    "               and are held before the first and after the last; a lights entry replaces the\n"
    "               scene's punctual lights from its frame on. Where two steps have the same camera and\n"
    "               lights (before the first key, after the last) the renderer sees a still view, as\n"
    "               with --frames: the frames average (--set accumulate=0: each frame alone) and a\n"
    "               progressive technique keeps accumulating; any change starts again from one frame.\n"
    "               --out is then a folder [out/sequence]: DIR/frame-NNNN.exr (frame number, %04d) for\n"
    "               frames 0, K, 2K, ... and the last, and DIR/sequence.json with the run's record and\n"
    "               \"frames\": [{\"index\": i, \"ms\": the GPU ms of frame i's passes}, ...] for every\n"
    "               frame. --frames, --warmup, --camera, --light, --json, --reference and --exposure\n"
    "               are refused with it.\n"
    "  --every      with --path: write every K-th frame (and the last)         [1]\n"
    "  --indirect-scale  the technique's indirect light at 1/N of the resolution (1..16),\n"
    "               joint-bilaterally upsampled, as the demo's budget does while moving [1]\n";

namespace {

// What each option refused with --path would have meant, and why it has no meaning there.
void refuseStillOptions(const Options& o)
{
    const struct {
        const char* option;
        const char* why;
    } refused[] = {
        {"frames", "the path gives the frame count"},
        {"warmup", "a sequence has no warm-up: frame 0 is the path's first"},
        {"camera", "the path gives the camera"},
        {"light", "the path gives the lights (its \"lights\" entries)"},
        {"json", "the record is DIR/sequence.json"},
        {"reference", "a sequence has no single reference"},
        {"exposure", "a sequence writes EXR only"},
    };
    for (const auto& r : refused)
        if (o.has(r.option)) throw UsageError(std::string("--") + r.option + " cannot be given with --path: " + r.why);
}

std::string frameFileName(int frame)
{
    char name[32];
    std::snprintf(name, sizeof name, "frame-%04d.exr", frame);
    return name;
}

} // namespace

SceneOnPath sceneOnPath(core::Scene scene, const core::CameraPath& path, const std::string& pathFile)
{
    const core::Bounds b = scene.bounds();
    const float diagonal = glm::length(b.extent());
    for (int f = 0; f < path.frames; ++f)
        scene.camera.zfar = std::max(scene.camera.zfar, glm::length(path.at(f).position - b.centre()) + diagonal);
    SceneOnPath s;
    s.base = scene.camera;
    scene.camera = path.camera(0, s.base);
    scene.cameraSource = "path " + pathFile;
    if (const std::vector<core::Light>* lights = path.lightsAt(0)) scene.lights = *lights;
    s.scene = std::move(scene);
    return s;
}

core::Scene SceneOnPath::at(const core::CameraPath& path, int frame) const
{
    core::Scene s = scene;
    s.camera = path.camera(frame, base);
    // Before the first "lights" entry lightsAt is null and frame 0's lights (the scene's own) hold.
    if (const std::vector<core::Light>* lights = path.lightsAt(frame)) s.lights = *lights;
    return s;
}

void stepAlongPath(gl::Renderer& renderer, const SceneOnPath& onPath, const core::CameraPath& path, int frame)
{
    renderer.frame().setCamera(path.camera(frame, onPath.base));
    if (path.lightsChangeAt(frame)) renderer.frame().setLights(*path.lightsAt(frame));
}

int renderSequence(const Options& o)
{
    // Everything the user gave is checked before anything is created or written.
    refuseStillOptions(o);
    int width = 512, height = 512;
    if (o.has("size")) parseSize(o.get("size"), width, height);
    const int every = o.getInt("every", 1, 1, 100000);
    const int indirectScale = o.getInt("indirect-scale", 1, 1, 16);
    const fs::path out = o.get("out", "out/sequence");
    if (out.extension() == ".exr" || out.extension() == ".png")
        throw UsageError("with --path, --out is a folder (DIR/frame-NNNN.exr, DIR/sequence.json), not '" +
                         out.string() + "'");
    if (fs::exists(out) && !fs::is_directory(out))
        throw UsageError("with --path, --out is a folder, and '" + out.string() + "' is a file");
    const std::string pathFile = o.get("path");
    core::CameraPath path;
    try {
        path = core::loadCameraPath(pathFile);
    } catch (const core::CameraPathError& e) {
        throw UsageError(std::string("--path: ") + e.what());
    }
    const std::string sceneArg = o.get("scene", "cornell-spot");
    const std::string techniqueName = o.get("technique", "direct");
    CliTechnique chosen = techniqueForCli(techniqueName, o.all("set"));
    gl::ParamValues& frameValues = chosen.frameValues;
    gl::ParamValues& techniqueValues = chosen.techniqueValues;
    SceneOnPath onPath = sceneOnPath(loadSceneForCli(sceneArg), path, pathFile);
    core::Scene& scene = onPath.scene;
    applySceneOptions(scene, "", {});
    const fs::path recordFile = out / "sequence.json";
    try {
        core::checkOutputPath(recordFile.string());
    } catch (const core::ImageError& e) {
        throw UsageError(e.what());
    }

    auto context = createContextForCli(o.get("backend", "egl"), o.get("backend") == "glfw");
    std::printf("GL renderer: %s (%s, %s)\n", context->info().renderer.c_str(), context->info().platform.c_str(),
                context->info().version.c_str());
    const std::unique_ptr<gl::Renderer> made =
        makeRendererForCli(scene, techniqueName, frameValues, techniqueValues, width, height, indirectScale);
    gl::Renderer& renderer = *made;

    nlohmann::json frames = nlohmann::json::array(), written = nlohmann::json::array();
    std::size_t nonFinite = 0;
    {
        core::Progress progress("render --path", double(path.frames), "frames");
        for (int f = 0; f < path.frames; ++f) {
            if (f > 0) stepAlongPath(renderer, onPath, path, f);
            renderer.renderFrame(true);
            double ms = 0.0;
            for (const gl::PassStat& p : renderer.timers().lastFrame()) ms += p.medianMs;
            frames.push_back({{"index", f}, {"ms", ms}});
            if (f % every == 0 || f == path.frames - 1) {
                const core::Image image = renderer.image();
                nonFinite += nonFiniteValues(image);
                const fs::path file = out / frameFileName(f);
                core::FileSet files;
                files.addImage(file.string(), image);
                try {
                    files.commit();
                } catch (const core::ImageError& e) {
                    std::fprintf(stderr, "bounce render: error: %s\n", e.what());
                    return 1;
                }
                written.push_back(file.filename().string());
            }
            progress.add(1.0);
        }
    }

    nlohmann::json record = runRecord(context->info(), sceneArg, renderer);
    record["path"] = pathFile;
    record["frameCount"] = path.frames;
    record["every"] = every;
    record["indirectScale"] = indirectScale;
    record["written"] = written;
    record["frames"] = frames;
    // Over the frames written (runRecord's figure is the last frame's).
    record["nonFiniteValues"] = nonFinite;
    core::FileSet files;
    files.add(recordFile.string(), recordText(record));
    try {
        files.commit();
    } catch (const core::ImageError& e) {
        throw UsageError(e.what());
    }

    std::printf("%s on %s along %s, %dx%d, %d frames (indirect light at 1/%d):\n", techniqueName.c_str(),
                sceneArg.c_str(), pathFile.c_str(), width, height, path.frames, indirectScale);
    printPassTable(renderer, context->info().renderer);
    std::printf("wrote %zu frames and %s\n", written.size(), recordFile.string().c_str());
    if (nonFinite > 0) {
        std::fprintf(stderr, "bounce render: error: the frames written have %zu non-finite (NaN/Inf) values\n",
                     nonFinite);
        return 1;
    }
    return 0;
}

} // namespace bounce::app
