// The demo's camera: right mouse drag looks around, W/A/S/D move in the view plane, Q/E down and up.
#pragma once

#include "core/scene.h"

struct GLFWwindow;

namespace bounce::app {

class FlyCamera {
public:
    explicit FlyCamera(const core::Camera& camera);
    const core::Camera& camera() const { return camera_; }
    // Reads the mouse and keys (unless the panel has them); returns true when the camera moved.
    bool update(GLFWwindow* window, float dtSeconds, float speedMPerS);
    // Moves the camera sideways by `metres` (the demo script's move: step, as the D key would).
    void strafe(float metres);

private:
    core::Camera camera_;
    float yaw_ = 0, pitch_ = 0;
    double lastX_ = 0, lastY_ = 0;
};

} // namespace bounce::app
