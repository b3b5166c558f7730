// The lights as every shader reads them (glsl/common/scene.glsl's Light, SSBO_LIGHTS): one record per light
// of GpuScene::lights(), owned by the frame. ShadowMaps writes them (it assigns each light its shadow
// layers, and in still frames moves an emitting mesh's lights to that frame's point on it); every pass that
// shades with the lights binds them through Frame::bindSceneData and counts them here.
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
static_assert(sizeof(GpuLight) == 80, "scene.glsl's Light: 80 bytes in std430");

class FrameLights {
public:
    // Uploads the records (in place while the count holds); an empty list uploads one unused record, since a
    // storage buffer may not be empty.
    void set(const std::vector<GpuLight>& lights);
    // At SSBO_LIGHTS.
    void bind() const;
    int count() const { return int(lights_.size()); }
    const std::vector<GpuLight>& lights() const { return lights_; }

private:
    std::vector<GpuLight> lights_;
    Buffer buffer_;
};

} // namespace bounce::gl
