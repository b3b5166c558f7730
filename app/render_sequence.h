// bounce render --path: a camera path rendered frame by frame (issue 58, "Sequences"), one frame per step
// with no still frames, its frames as EXR (every K-th and the last) and a record of every frame's GPU time.
#pragma once

#include <string>

#include "app/options.h"
#include "core/camera_path.h"
#include "core/scene.h"
#include "gl/renderer.h"

namespace bounce::app {

// The --help lines of --path, --every and --indirect-scale.
extern const char* const kSequenceOptionsHelp;

// A scene made ready for a camera path: the far plane beyond the whole scene from every position on the
// path (a setup sets it from its own camera only), the camera and the lights of frame 0.
struct SceneOnPath {
    core::Scene scene; // at frame 0
    core::Camera base; // the scene's camera with that far plane: every frame's near and far planes
    // The scene as frame `frame` sees it: its camera and punctual lights (what its reference renders).
    core::Scene at(const core::CameraPath& path, int frame) const;
};
SceneOnPath sceneOnPath(core::Scene scene, const core::CameraPath& path, const std::string& pathFile);

// Gives the renderer frame `frame`'s camera, and its lights where a "lights" entry starts there.
void stepAlongPath(gl::Renderer& renderer, const SceneOnPath& onPath, const core::CameraPath& path, int frame);

// Runs `bounce render` with --path given: the options are render's. Returns the exit status; bad input
// (the path file, a refused option, an --out that is not a folder) throws UsageError before anything is
// written.
int renderSequence(const Options& o);

} // namespace bounce::app
