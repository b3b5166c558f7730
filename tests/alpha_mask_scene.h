// The alpha-masked quad every suite tests masks with (core I/O, the path tracer, the rasteriser, GPU ray
// casting): a 1 m square at height 1.5, x and z in [-0.5, 0.5], double-sided, glTF alphaMode MASK with
// cutoff 0.5 and a 4x4 RGBA texture whose left half (u < 0.5, x < 0) has alpha 0 and right half alpha
// 255 (u = x + 0.5, v = z + 0.5). Light from above passes through the left half only.
#pragma once

#include <cstdint>

#include "core/scene.h"

namespace bounce::testing {

inline constexpr float kMaskQuadHeight = 1.5f;

inline core::Texture maskTexture()
{
    core::Texture t;
    t.name = "half-mask";
    t.width = 4;
    t.height = 4;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const std::uint8_t alpha = x < 2 ? 0 : 255;
            t.rgba8.insert(t.rgba8.end(), {60, 200, 60, alpha});
        }
    return t;
}

// Appends the masked quad (its material and texture) to `scene`.
inline void addMaskedQuad(core::Scene& scene)
{
    core::Material m;
    m.name = "mask";
    m.specular = 0.0f;
    m.doubleSided = true;
    m.alphaMode = core::AlphaMode::Mask;
    m.alphaCutoff = 0.5f;
    m.baseColorTexture = int(scene.textures.size());
    scene.textures.push_back(maskTexture());
    scene.materials.push_back(m);
    core::Mesh q;
    q.name = "mask";
    q.material = std::uint32_t(scene.materials.size() - 1);
    const float y = kMaskQuadHeight;
    q.positions = {{-0.5f, y, -0.5f}, {0.5f, y, -0.5f}, {0.5f, y, 0.5f}, {-0.5f, y, 0.5f}};
    q.normals.assign(4, glm::vec3(0.0f, -1.0f, 0.0f)); // faces the floor
    q.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
    q.indices = {0, 1, 2, 0, 2, 3}; // counter-clockwise seen from below
    scene.meshes.push_back(q);
}

} // namespace bounce::testing
