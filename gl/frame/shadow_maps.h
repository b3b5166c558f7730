// Shadow maps of every light in one depth array texture, one layer per view of gl/frame/light_views.h:
// a spot gets one perspective layer (a cube when its cone is wider than 120 degrees), a point light six cube-face layers, the area lights of one
// emitting mesh one shared cube at its centroid, a directional light one orthographic layer fitted to
// the scene. Also owns the light SSBOs of glsl/common/scene.glsl. Only what the lights need is allocated.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "gl/frame/gpu_scene.h"
#include "gl/frame/light_views.h"
#include "gl/frame/scene_program.h"
#include "gl/resource/buffer.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"

namespace bounce::gl {

struct ShadowView {
    glm::mat4 view{1.0f};
    glm::mat4 proj{1.0f};
    glm::vec3 origin{0.0f};
    float far = 0.0f;        // 0 for orthographic
    float texelWorld = 0.0f; // world size of a texel at distance 1 (perspective) or absolute (orthographic)
};

class ShadowMaps {
public:
    ShadowMaps(const GpuScene& scene, int size);
    // Recomputes views and light buffers after lights moved (keeps the texture when the layer count holds).
    void update(const GpuScene& scene);
    void render(const GpuScene& scene);
    // SSBO bindings 1 (lights), 2 (shadow views), 3 (area polygons) and the depth array at unit 5.
    void bind() const;
    void setPcf(bool hardwareFilter);
    // The PCF uniforms of glsl/common/shadow.glsl on a program that includes it: the kernel radius, and
    // whether the taps are nearest (the shader gathers texels itself and weights them as the filter would).
    void setPcfUniforms(Program& program, int radius) const;

    int lightCount() const { return int(gpuLights_.size()); }
    const std::vector<GpuLight>& gpuLights() const { return gpuLights_; }
    const std::vector<ShadowView>& views() const { return views_; }
    const Texture& depth() const { return depth_; }
    int size() const { return size_; }

private:
    int size_;
    std::vector<ShadowView> views_;
    std::vector<GpuLight> gpuLights_;
    Texture depth_;
    Framebuffer fbo_;
    SceneProgram program_;
    Buffer lightsBuffer_, viewsBuffer_, polygonsBuffer_;
    bool linear_ = true;
    void buildViews(const GpuScene& scene);
};

} // namespace bounce::gl
