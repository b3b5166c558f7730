// The frame every technique shares (DESIGN.md, data flow): the scene on the GPU, shadow maps, the
// G-buffer, direct light, and the indirect-light texture a technique writes; composite = direct +
// indirect. Passes are timed through PassTimers under stable names ("shadow", "gbuffer", "direct"...).
#pragma once

#include <cstdint>
#include <memory>

#include <glm/glm.hpp>

#include "core/image.h"
#include "core/scene.h"
#include "gl/frame/gpu_scene.h"
#include "gl/frame/scene_program.h"
#include "gl/frame/shadow_maps.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

struct FrameSettings {
    int width = 512;
    int height = 512;
    int shadowMapSize = 1024;
    int pcfRadius = 1;     // 0: one hard tap per pixel
    bool pcfLinear = true; // hardware 2x2 bilinear comparison
    int textureSize = 512; // base-colour textures are resampled to this size
    // Profiling only (bench/sponza-gbuffer.json): the G-buffer pass with a fragment shader that writes
    // constants, to tell fragment work from vertex work and triangle setup. The images are wrong.
    bool gbufferConstantFragment = false;
};

// Counters that change when the scene, a light or the camera moves (and only then): progressive
// techniques compare them with what they accumulated for and start over.
struct FrameVersion {
    std::uint64_t scene = 0;  // geometry and materials (a Frame holds one scene: changes once scenes move)
    std::uint64_t lights = 0; // setLights()
    std::uint64_t camera = 0; // setCamera() with a different camera, resize()
    bool operator==(const FrameVersion&) const = default;
};

class Frame {
public:
    Frame(const core::Scene& scene, const FrameSettings& settings);

    void setCamera(const core::Camera& camera);
    void setLights(const std::vector<core::Light>& lights); // moves punctual lights, re-renders shadows
    void resize(int width, int height);

    // The frame's own passes, in order: shadow maps, G-buffer, direct light. Then the technique runs,
    // then composite(). frameIndex counts calls to beginFrame().
    void beginFrame();
    void renderShadowMaps(PassTimers& timers);
    void renderGBuffer(PassTimers& timers);
    void renderDirect(PassTimers& timers);
    void composite(PassTimers& timers);
    void clearIndirect();

    // Binds the G-buffer at texture units 0..4 (glsl/common/gbuffer.glsl).
    void bindGBuffer() const;
    // Binds materials (SSBO 0), lights (1), shadow views (2), area polygons (3), the scene's geometry
    // (vertices 4, indices 5, emissive triangles 6: glsl/common/scene.glsl with SCENE_GEOMETRY), shadow
    // depth (unit 5) and the base-colour textures (unit 6).
    void bindSceneData() const;
    void drawFullscreen() const;

    const core::Scene& scene() const { return scene_; }
    const GpuScene& gpuScene() const { return gpu_; }
    const ShadowMaps& shadowMaps() const { return shadows_; }
    const FrameSettings& settings() const { return settings_; }
    const core::Camera& camera() const { return camera_; }
    glm::mat4 view() const { return camera_.view(); }
    glm::mat4 projection() const { return camera_.projection(float(settings_.width) / float(settings_.height)); }
    int width() const { return settings_.width; }
    int height() const { return settings_.height; }
    int frameIndex() const { return frameIndex_; }
    const FrameVersion& version() const { return version_; }

    const Texture& position() const { return position_; }
    const Texture& normal() const { return normal_; }
    const Texture& diffuse() const { return diffuse_; }
    const Texture& specular() const { return specular_; }
    const Texture& emission() const { return emission_; }
    const Texture& depth() const { return depth_; }
    const Texture& direct() const { return direct_; }
    Texture& indirect() { return indirect_; }
    const Texture& result() const { return composite_; }

    // Reads an RGBA32F texture back as an RGB image, row 0 at the top.
    core::Image read(const Texture& texture) const;

private:
    const core::Scene& scene_;
    FrameSettings settings_;
    core::Camera camera_;
    GpuScene gpu_;
    ShadowMaps shadows_;
    Texture position_, normal_, diffuse_, specular_, emission_, depth_, direct_, indirect_, composite_;
    Framebuffer gbufferFbo_, directFbo_, compositeFbo_;
    VertexArray emptyVao_;
    SceneProgram gbufferProgram_;
    Program directProgram_, compositeProgram_;
    int frameIndex_ = -1;
    FrameVersion version_;
    void allocateTargets();
};

} // namespace bounce::gl
