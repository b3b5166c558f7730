// Texture lookups on the CPU, as the GPU's sampler2DArray reads the scene's textures: bilinear with repeat
// wrapping, texel centres at half-integers, row 0 at v = 0 (glTF). The path tracer (ref/embree_scene.cpp)
// shades and cuts alpha masks with them; the surface sampler (core/surface_points.h) cuts the masks' holes
// out of the point clouds.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace bounce::core {

template <class T>
T bilinearRepeat(const std::vector<T>& texels, int width, int height, const glm::vec2& uv)
{
    const float x = uv.x * float(width) - 0.5f;
    const float y = uv.y * float(height) - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float ax = x - fx, ay = y - fy;
    const auto wrap = [](long i, int n) { return int(((i % n) + n) % n); };
    const int x0 = wrap(long(fx), width), x1 = wrap(long(fx) + 1, width);
    const int y0 = wrap(long(fy), height), y1 = wrap(long(fy) + 1, height);
    const auto at = [&](int xx, int yy) { return texels[std::size_t(yy) * std::size_t(width) + std::size_t(xx)]; };
    return glm::mix(glm::mix(at(x0, y0), at(x1, y0), ax), glm::mix(at(x0, y1), at(x1, y1), ax), ay);
}

// The holes of a scene's alpha-masked materials (Material::cutsOut): the alpha of each masked material's
// base-colour texture, as floats.
class AlphaMasks {
public:
    explicit AlphaMasks(const Scene& scene);

    bool any() const { return any_; }
    // The alpha of m's base-colour texture at uv (1 without a texture, or for a material that is not masked).
    float alpha(const Material& m, const glm::vec2& uv) const;
    // Whether uv lies in a hole of m's mask.
    bool cutOut(const Material& m, const glm::vec2& uv) const { return m.isMasked() && m.cutsOut(alpha(m, uv)); }

private:
    struct Alpha {
        int width = 0, height = 0;
        std::vector<float> values; // 0..1; empty for textures no masked material uses
    };
    std::vector<Alpha> textures_;
    bool any_ = false;
};

} // namespace bounce::core
