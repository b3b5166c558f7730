// Camera paths for `bounce render --path` (issue 58, "Sequences"): the camera and the punctual lights of
// every frame of a sequence, from a small JSON file.
//
//   {
//     "frames": 120,                                         N >= 1: frames 0..N-1
//     "keys": [{"frame": 0, "camera": "0.278,0.273,-0.8:0.278,0.273,0:39.3"}, ...],
//     "lights": [{"frame": 30, "light": ["spot:position=...;direction=0,-1,0;intensity=0.2"]}]   optional
//   }
//
// "camera" is the command line's --camera POSITION:TARGET:FOV_DEGREES (cameraJsonFromArgument), except that
// every key gives the field of view; "light" holds --light specs (lightJsonFromArgument), point, spot and
// directional only (an area light is geometry, which a path does not move). The parsing is the
// command line's own, so a path accepts and refuses what --camera and --light do.
//
// Position, target and field of view interpolate linearly between keys and are held before the first key
// and after the last. The lights of a "lights" entry replace the scene's punctual lights from its frame on
// (an empty list: no punctual light); before the first entry the scene keeps its own.
//
// Refused (CameraPathError, naming the file, the entry and the problem): malformed JSON, unknown or missing
// keys, frames < 1, key or light frames that are not integers, not strictly increasing, or outside
// 0..N-1 (a key the sequence never reaches is a mistake more often than a way to cut a longer path), NaN or
// Inf anywhere, a field of view outside (0, 180), and a zero-length view (position == target) or a view
// along the world's up axis (the camera's up is +y) at any key or at any frame between keys.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/scene.h"

namespace bounce::core {

struct CameraPathError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct CameraKey {
    int frame = 0;
    glm::vec3 position{0.0f}, target{0.0f, 0.0f, 1.0f};
    float yfovDeg = 40.0f;
};

struct LightKey {
    int frame = 0;
    std::vector<Light> lights; // punctual only
};

struct CameraPath {
    int frames = 1;
    std::vector<CameraKey> keys;     // at least one, frames strictly increasing
    std::vector<LightKey> lightKeys; // frames strictly increasing; may be empty

    // Position, target and field of view at `frame` (linear between keys, held outside them).
    CameraKey at(int frame) const;
    // The camera at `frame`: `base` (the scene's camera) for the near and far planes, +y as up.
    Camera camera(int frame, const Camera& base) const;
    // The punctual lights from `frame` on, or nullptr before the first "lights" entry (the scene's own).
    const std::vector<Light>* lightsAt(int frame) const;
    // Whether a "lights" entry starts at exactly `frame`.
    bool lightsChangeAt(int frame) const;
};

// `where` names the source (the file) in error messages.
CameraPath parseCameraPath(const nlohmann::json& path, const std::string& where);
CameraPath loadCameraPath(const std::string& file);

} // namespace bounce::core
