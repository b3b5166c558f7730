#include "core/texture_sampling.h"

namespace bounce::core {

AlphaMasks::AlphaMasks(const Scene& scene) : textures_(scene.textures.size())
{
    for (const Material& m : scene.materials) {
        if (!m.isMasked()) continue;
        any_ = true;
        if (m.baseColorTexture < 0 || std::size_t(m.baseColorTexture) >= scene.textures.size()) continue;
        const Texture& t = scene.textures[std::size_t(m.baseColorTexture)];
        Alpha& a = textures_[std::size_t(m.baseColorTexture)];
        if (!a.values.empty() || t.width <= 0 || t.height <= 0 ||
            t.rgba8.size() < std::size_t(t.width) * std::size_t(t.height) * 4)
            continue;
        a.width = t.width;
        a.height = t.height;
        a.values.resize(std::size_t(t.width) * std::size_t(t.height));
        for (std::size_t p = 0; p < a.values.size(); ++p) a.values[p] = float(t.rgba8[4 * p + 3]) / 255.0f;
    }
}

float AlphaMasks::alpha(const Material& m, const glm::vec2& uv) const
{
    if (m.baseColorTexture < 0 || std::size_t(m.baseColorTexture) >= textures_.size()) return 1.0f;
    const Alpha& a = textures_[std::size_t(m.baseColorTexture)];
    if (a.values.empty()) return 1.0f;
    return bilinearRepeat(a.values, a.width, a.height, uv);
}

} // namespace bounce::core
