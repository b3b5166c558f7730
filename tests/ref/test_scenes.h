// Scenes built in code for the reference tests: planes, a closed sphere, a small box room. Every
// triangle gets the flat normal of its counter-clockwise winding, so geometric and shading normals agree.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image.h"
#include "core/metrics.h"
#include "core/scene.h"
#include "ref/reference.h"

namespace bounce::testing {

inline std::uint32_t addMaterial(core::Scene& s, const core::Material& m)
{
    s.materials.push_back(m);
    return std::uint32_t(s.materials.size() - 1);
}

inline core::Material lambertian(const glm::vec3& albedo, const glm::vec3& emission = glm::vec3(0.0f))
{
    core::Material m;
    m.baseColor = albedo;
    m.specular = 0.0f;
    m.metallic = 0.0f;
    m.emission = emission;
    return m;
}

// The quad (v0, v1, v2, v3) as triangles (v0, v1, v2) and (v0, v2, v3), front face counter-clockwise.
inline void addQuad(core::Scene& s, std::uint32_t material, const glm::vec3& v0, const glm::vec3& v1,
                    const glm::vec3& v2, const glm::vec3& v3, const std::string& name = "quad")
{
    core::Mesh m;
    m.name = name;
    m.material = material;
    const glm::vec3 n = glm::normalize(glm::cross(v1 - v0, v2 - v0));
    m.positions = {v0, v1, v2, v3};
    m.normals = {n, n, n, n};
    m.indices = {0, 1, 2, 0, 2, 3};
    s.meshes.push_back(m);
}

// A horizontal square at height y, centred on (cx, cz), half size h, facing +y (up) or -y (down).
inline void addHorizontalSquare(core::Scene& s, std::uint32_t material, float y, float h, bool up, float cx = 0.0f,
                                float cz = 0.0f)
{
    const glm::vec3 a(cx - h, y, cz - h), b(cx - h, y, cz + h), c(cx + h, y, cz + h), d(cx + h, y, cz - h);
    if (up)
        addQuad(s, material, a, b, c, d);
    else
        addQuad(s, material, a, d, c, b);
}

// A closed UV sphere of flat triangles facing inwards (towards the centre).
inline void addInwardSphere(core::Scene& s, std::uint32_t material, float radius, int rings, int segments)
{
    core::Mesh m;
    m.name = "sphere";
    m.material = material;
    const auto point = [&](int i, int j) {
        const float theta = core::kPi * float(i) / float(rings), phi = 2.0f * core::kPi * float(j) / float(segments);
        return radius * glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    };
    const auto tri = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
        glm::vec3 n = glm::cross(b - a, c - a);
        if (glm::dot(n, a + b + c) > 0.0f) {
            std::swap(b, c);
            n = -n;
        } // make the front face the inside
        n = glm::normalize(n);
        const auto base = std::uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(), {a, b, c});
        m.normals.insert(m.normals.end(), {n, n, n});
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
    };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const glm::vec3 p00 = point(i, j), p01 = point(i, j + 1), p10 = point(i + 1, j), p11 = point(i + 1, j + 1);
            if (i > 0) tri(p00, p10, p01);
            if (i < rings - 1) tri(p01, p10, p11);
        }
    s.meshes.push_back(m);
}

// A camera at `position` looking straight down (-y), image up = +z.
inline core::Camera cameraLookingDown(const glm::vec3& position, float yfovRad)
{
    core::Camera c;
    c.position = position;
    c.forward = {0.0f, -1.0f, 0.0f};
    c.up = {0.0f, 0.0f, 1.0f};
    c.yfovRad = yfovRad;
    return c;
}

// A 1 m box room seen through its open front (z = 0) from z = -1.3: white floor, ceiling and back wall,
// red and green side walls, a white block, and either a 0.3 m square area light just under the ceiling
// or a point light. Small and fast, with occlusion and colour bleeding like the Cornell box.
inline core::Scene boxRoom(bool areaLight, bool block = true)
{
    core::Scene s;
    const auto white = addMaterial(s, lambertian({0.7f, 0.7f, 0.7f}));
    const auto red = addMaterial(s, lambertian({0.6f, 0.1f, 0.1f}));
    const auto green = addMaterial(s, lambertian({0.1f, 0.5f, 0.1f}));
    const glm::vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    addQuad(s, white, o, z, x + z, x, "floor");               // normal +y
    addQuad(s, white, y, y + x, y + x + z, y + z, "ceiling"); // normal -y
    addQuad(s, white, z, z + y, z + x + y, z + x, "back");    // normal -z
    addQuad(s, red, o, y, y + z, z, "left");                  // normal +x
    addQuad(s, green, x, x + z, x + y + z, x + y, "right");   // normal -x
    if (block) {
        // A 0.3 x 0.5 x 0.3 box standing on the floor, faces outwards.
        const glm::vec3 lo(0.55f, 0.0f, 0.45f), hi(0.85f, 0.5f, 0.75f);
        const glm::vec3 a(lo.x, lo.y, lo.z), b(hi.x, lo.y, lo.z), c(hi.x, lo.y, hi.z), d(lo.x, lo.y, hi.z);
        const glm::vec3 e(lo.x, hi.y, lo.z), f(hi.x, hi.y, lo.z), g(hi.x, hi.y, hi.z), h(lo.x, hi.y, hi.z);
        addQuad(s, white, e, h, g, f, "block top");   // +y
        addQuad(s, white, a, e, f, b, "block front"); // -z
        addQuad(s, white, b, f, g, c, "block right"); // +x
        addQuad(s, white, c, g, h, d, "block back");  // +z
        addQuad(s, white, d, h, e, a, "block left");  // -x
    }
    if (areaLight) {
        const auto light = addMaterial(s, lambertian(glm::vec3(0.0f), glm::vec3(12.0f, 10.0f, 8.0f)));
        addHorizontalSquare(s, light, 0.999f, 0.15f, false, 0.5f, 0.5f);
    } else {
        core::Light l;
        l.type = core::LightType::Point;
        l.position = {0.5f, 0.8f, 0.5f};
        l.intensity = glm::vec3(0.3f);
        s.lights.push_back(l);
    }
    s.camera.position = {0.5f, 0.5f, -1.3f};
    s.camera.forward = {0.0f, 0.0f, 1.0f};
    s.camera.up = {0.0f, 1.0f, 0.0f};
    s.camera.yfovRad = 2.0f * std::atan(0.5f / 1.3f);
    return s;
}

inline ref::RenderSettings settings(ref::LightPaths paths, int size, int spp, std::uint64_t seed = 1)
{
    ref::RenderSettings r;
    r.paths = paths;
    r.width = r.height = size;
    r.spp = spp;
    r.seed = seed;
    r.threads = 2;
    r.progress = false;
    return r;
}

inline double imageMean(const core::Image& im, int channel = -1)
{
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < im.rgb.size(); ++i)
        if (channel < 0 || int(i % 3) == channel) {
            sum += im.rgb[i];
            ++n;
        }
    return sum / double(n);
}

// The standard error of imageMean over all channels, from the per-pixel variance image (pixels are
// independent: they use disjoint random streams).
inline double imageMeanStdErr(const core::Image& variance)
{
    double sum = 0.0;
    for (float v : variance.rgb) sum += v;
    return std::sqrt(sum) / double(variance.rgb.size());
}

} // namespace bounce::testing
