// What the point-based gathers' tests share (microrender_test.cpp, pointproj_test.cpp): a closed furnace
// box, rendering a technique and reading its indirect light and counters, and the path tracer's
// one-bounce indirect light of the same view (cached on disk).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "core/scene.h"
#include "gl/renderer.h"
#include "ref/reference.h"
#include "tests/gl/closed_box.h"
#include "tests/gl/moved_scene.h"
#include "tests/image_expect.h"

namespace bounce::testing {

using Sets = std::vector<std::pair<std::string, std::string>>;

struct PointRender {
    core::Image indirect;
    core::Image mask;   // 1 where the G-buffer has geometry
    core::Image glossy; // the G-buffer's specular weight w (1 on cornell-glossy's metal block)
    std::vector<gl::Counter> counters;
    double counter(const std::string& name) const;
};

// std430 mirror of point_cloud.glsl's PointSurfel, as the tests download the cloud's surfels.
struct PointSurfel {
    glm::vec3 position;
    float areaM2;
    glm::vec3 normal;
    std::uint32_t diffuse; // c_diff as unorm 8-bit RGB
};
static_assert(sizeof(PointSurfel) == 32, "point_cloud.glsl's PointSurfel");

// An IEEE half float (the low 16 bits of h), as the point buffers pack radiance and lobes (packHalf2x16).
inline float halfToFloat(std::uint32_t h)
{
    const std::uint32_t s = (h >> 15) & 1u, e = (h >> 10) & 31u, m = h & 1023u;
    float v = e == 0 ? std::ldexp(float(m), -24) : (e == 31 ? INFINITY : std::ldexp(float(m | 1024u), int(e) - 25));
    return s ? -v : v;
}

// The furnace: a closed box, every surface albedo rho emitting L_e. One bounce of indirect light is
// exactly rho^2 L_e everywhere (every point reflects rho L_e, and every direction sees a point).
inline core::Scene pointFurnaceBox(float rho, float emission)
{
    return closedBox("point-furnace", rho, emission);
}

inline double PointRender::counter(const std::string& name) const
{
    for (const gl::Counter& c : counters)
        if (c.name == name) return c.value;
    return -1.0;
}

// Renders `frames` frames of `technique` with its defaults changed by `sets` (shadow maps 512^2); with `moved`,
// one frame first, then the scene's vertices moved there (gl::Renderer::moveVertices), then the frames.
inline PointRender renderPoints(const core::Scene& scene, const std::string& technique, const Sets& sets, int w, int h,
                                int frames = 1, const MovedVertices* moved = nullptr)
{
    const gl::TechniqueInfo& info = gl::findTechnique(technique);
    gl::ParamValues frameValues(gl::frameParams()), values(info.params);
    frameValues.setValue("shadow.size", 512);
    for (const auto& [k, v] : sets) values.set(info.params, k, v);
    gl::Renderer r(scene, technique, frameValues, values, w, h);
    if (moved) {
        r.renderFrame();
        if (!r.moveVertices(moved->positions, moved->normals)) throw std::invalid_argument("vertices not moved");
    }
    for (int f = 0; f < frames; ++f) r.renderFrame();
    PointRender out{r.frame().read(r.frame().indirect()), core::Image(w, h), core::Image(w, h), r.counters()};
    const std::vector<float> p = r.frame().readPositions();
    const std::vector<float> d = r.frame().diffuse().readFloats(0, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            out.mask.set(x, h - 1 - y, glm::vec3(p[(std::size_t(y) * w + x) * 4 + 3]));
            out.glossy.set(x, h - 1 - y, glm::vec3(d[(std::size_t(y) * w + x) * 4 + 3]));
        }
    return out;
}

// The path tracer's onebounce-indirect light (what a point gather adds to `direct`), `spp` samples.
inline core::Image pathTracedOneBounce(const core::Scene& scene, int w, int h, int spp)
{
    ref::RenderSettings s;
    s.paths = ref::LightPaths::OneBounceIndirect;
    s.width = w;
    s.height = h;
    s.spp = spp;
    s.seed = 5;
    s.progress = false;
    const ref::RenderResult r = ref::cachedReference(scene, scene.camera, s);
    std::printf("[ reference] %s onebounce-indirect %dx%d, %d spp%s\n", scene.name.c_str(), w, h, r.spp,
                r.fromCache ? " (cached)" : "");
    return r.image;
}

inline double meanOver(const core::Image& img, const core::Image& mask, int channel)
{
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (mask.at(x, y).x > 0.0f) {
                sum += img.at(x, y)[channel];
                ++n;
            }
    return n ? sum / n : 0.0;
}

inline bool allFiniteNonNegative(const core::Image& img)
{
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(img.at(x, y)[c]) || img.at(x, y)[c] < 0.0f) return false;
    return true;
}

// The mean of the image's channels over a mask, and the error figures against the path tracer.
struct Versus {
    double meanRatio; // mean(got) / mean(want) over the mask
    double relRmse;
};

inline Versus versus(const core::Image& got, const core::Image& want, const std::vector<bool>& mask)
{
    double g = 0.0, w = 0.0;
    for (int y = 0; y < got.height; ++y)
        for (int x = 0; x < got.width; ++x)
            if (mask[std::size_t(y) * got.width + x])
                for (int c = 0; c < 3; ++c) g += got.at(x, y)[c], w += want.at(x, y)[c];
    return {w > 0.0 ? g / w : 0.0, measureImages(got, want, ImageMetric::relativeRmse(), &mask)};
}

// The mask m (> 0.5) without the pixels of `cut` (> 0.5).
inline core::Image without(core::Image m, const core::Image& cut)
{
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x)
            if (cut.at(x, y).x > 0.5f) m.set(x, y, glm::vec3(0.0f));
    return m;
}

// Pixels whose 3 x 3 neighbourhood lies inside `m` (> 0.5) and inside the image: the path tracer box-filters
// each pixel, the gather shades its centre, so pixels on a silhouette or on the image's border (the Cornell
// box's open front meets the border here) are left out.
inline std::vector<bool> interiorOf(const core::Image& m)
{
    std::vector<bool> out(std::size_t(m.width) * m.height, false);
    for (int y = 1; y + 1 < m.height; ++y)
        for (int x = 1; x + 1 < m.width; ++x) {
            bool all = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) all = all && m.at(x + dx, y + dy).x > 0.5f;
            out[std::size_t(y) * m.width + x] = all;
        }
    return out;
}

} // namespace bounce::testing
