// A program that rasterises the scene (the G-buffer, shadow maps, RSMs), in two variants where the scene
// has alpha-masked materials: its opaque meshes are drawn with the plain program, its masked ones with
// the ALPHA_MASK variant (glsl/common/base_color.glsl). Only masked surfaces then pay for the texture
// read and the discard, and the rest keep the early depth test a discard forbids; a scene without masks
// has the plain program alone.
#pragma once

#include <string>
#include <vector>

#include "gl/frame/gpu_scene.h"
#include "gl/resource/program.h"

namespace bounce::gl {

class SceneProgram {
public:
    SceneProgram() = default;
    // The plain variant; the masked one is made by prepare().
    SceneProgram(std::string label, std::string vertexPath, std::string fragmentPath, std::vector<Define> defines = {});

    // Makes the ALPHA_MASK variant when the scene needs it and it is not made yet.
    void prepare(const GpuScene& scene);

    // Sets a uniform in both variants.
    template <class T>
    void set(const std::string& name, const T& value)
    {
        plain_.set(name, value);
        if (masked_) masked_.set(name, value);
    }

    // Draws every triangle of the scene (prepare() first), each mesh with its variant.
    void draw(const GpuScene& scene) const;

private:
    std::string label_, vertexPath_, fragmentPath_;
    std::vector<Define> defines_;
    Program plain_, masked_;
};

} // namespace bounce::gl
