// The lights as every shader reads them (glsl/common/scene.glsl's frameLight, shadowView, lightPolygon;
// SSBO_LIGHTS), owned by the frame: one record per light of GpuScene::lights(), each light's shadow views, and
// the area lights' triangles, in one storage buffer, so that a pass that shades with the lights binds one
// block for them. ShadowMaps writes them (it assigns each light its shadow layers and views, and in still
// frames moves an emitting mesh's lights to that frame's point on it); every pass that shades with the lights
// binds them through Frame::bindSceneData and counts them here.
//
// The buffer, in vec4s: a header (x: the first vec4 of the shadow views, y: of the triangles' vertices,
// z: lights, w: views), then the lights (5 each), the views (6 each) and the vertices (1 each).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/resource/buffer.h"

namespace bounce::gl {

// std430 mirror of scene.glsl's Light: a named field for everything a shader reads, none packed into
// another's spare component.
struct GpuLight {
    glm::vec3 position{0.0f};        // point, spot: the light; area: the emitting mesh's point this frame (frame 0:
                                     // its centroid)
    std::int32_t type = 0;           // kLight* (gpu_scene.h)
    glm::vec3 direction{0.0f};       // spot, directional: the direction light travels; area: the emitter's normal
    float cosOuter = -1.0f;          // spot: cos of the outer cone's half angle
    glm::vec3 intensity{0.0f};       // W/sr (directional: W/m^2; area: radiance, W/(m^2 sr))
    float cosInner = -1.0f;          // spot: cos of the inner cone's half angle
    glm::ivec4 shadow{-1, 0, -1, 0}; // first shadow layer (-1: none), layer count, first polygon vertex, unused
    // Area lights in still frames: the emitting mesh's area on the one triangle that holds the frame's point
    // (common/lighting.glsl, areaSampleUnshadowed), 0 on every other light and in frame 0.
    float sampleArea = 0.0f;
    float pad0 = 0.0f, pad1 = 0.0f, pad2 = 0.0f;
};
static_assert(sizeof(GpuLight) == 80, "scene.glsl's frameLight: five vec4");

// One view a light's shadow layer is rendered from (scene.glsl's ShadowView).
struct GpuShadowView {
    glm::mat4 viewProj{1.0f};
    glm::vec4 originFar{0.0f};  // xyz the light's origin, w: far plane (perspective) or 0 (orthographic)
    glm::vec4 texelWorld{0.0f}; // x: a texel's world size at distance 1 (perspective) or absolute, y: the
                                // share of the layer's side the view is rendered at
};
static_assert(sizeof(GpuShadowView) == 96, "scene.glsl's shadowView: six vec4");

class FrameLights {
public:
    // Uploads the lights, their shadow views and the area lights' triangles (three vertices each, w 1), in
    // place while the sizes hold.
    void set(const std::vector<GpuLight>& lights, const std::vector<GpuShadowView>& views,
             const std::vector<glm::vec4>& polygons);
    // At SSBO_LIGHTS.
    void bind() const;
    int count() const { return int(lights_.size()); }
    const std::vector<GpuLight>& lights() const { return lights_; }

private:
    std::vector<GpuLight> lights_;
    Buffer buffer_;
};

} // namespace bounce::gl
