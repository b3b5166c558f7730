#include "app/fly_camera.h"

#include <cmath>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

namespace bounce::app {

FlyCamera::FlyCamera(const core::Camera& c) : camera_(c)
{
    yaw_ = std::atan2(c.forward.x, c.forward.z);
    pitch_ = std::asin(glm::clamp(c.forward.y, -1.0f, 1.0f));
}

bool FlyCamera::update(GLFWwindow* w, float dt, float speed)
{
    bool moved = false;
    double mx, my;
    glfwGetCursorPos(w, &mx, &my);
    if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS && !ImGui::GetIO().WantCaptureMouse) {
        yaw_ -= float(mx - lastX_) * 0.003f;
        pitch_ = glm::clamp(pitch_ - float(my - lastY_) * 0.003f, -1.5f, 1.5f);
        moved |= mx != lastX_ || my != lastY_;
    }
    lastX_ = mx;
    lastY_ = my;
    camera_.forward = {std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_), std::cos(pitch_) * std::cos(yaw_)};
    const glm::vec3 right = glm::normalize(glm::cross(camera_.forward, glm::vec3(0, 1, 0)));
    camera_.up = glm::normalize(glm::cross(right, camera_.forward));
    if (ImGui::GetIO().WantCaptureKeyboard) return moved;
    const struct {
        int key;
        glm::vec3 dir;
    } keys[] = {{GLFW_KEY_W, camera_.forward}, {GLFW_KEY_S, -camera_.forward},   {GLFW_KEY_D, right},
                {GLFW_KEY_A, -right},          {GLFW_KEY_E, glm::vec3(0, 1, 0)}, {GLFW_KEY_Q, glm::vec3(0, -1, 0)}};
    for (const auto& k : keys)
        if (glfwGetKey(w, k.key) == GLFW_PRESS) {
            camera_.position += k.dir * speed * dt;
            moved = true;
        }
    return moved;
}

void FlyCamera::strafe(float metres)
{
    camera_.position += glm::normalize(glm::cross(camera_.forward, glm::vec3(0, 1, 0))) * metres;
}

} // namespace bounce::app
