// A closed box [0, size]^3 for the GL tests' closed forms (furnaces, photon power): six inward-facing
// quads in one mesh (so that an emissive box shares one shadow cube), every surface Lambertian with
// albedo rho and emission L_e; the camera inside at (0.5, 0.5, 0.9) size, looking at a corner. No light:
// the caller adds what its case needs.
#pragma once

#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace bounce::testing {

// A quad (a, b, c, d) as two triangles, its front face where (b - a) x (c - a) points.
inline void addQuad(core::Mesh& m, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d)
{
    const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    const auto base = std::uint32_t(m.positions.size());
    for (const glm::vec3& p : {a, b, c, d}) {
        m.positions.push_back(p);
        m.normals.push_back(n);
    }
    for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
}

inline core::Scene closedBox(const std::string& name, float rho, float emission = 0.0f, float size = 1.0f)
{
    core::Scene s;
    s.name = name;
    core::Material m;
    m.name = "walls";
    m.baseColor = glm::vec3(rho);
    m.metallic = 0.0f;
    m.specular = 0.0f;
    m.emission = glm::vec3(emission);
    s.materials.push_back(m);
    core::Mesh mesh;
    mesh.name = "box";
    const auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
        addQuad(mesh, a * size, b * size, c * size, d * size);
    };
    // Counter-clockwise seen from inside: normals point into the box.
    quad({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}); // floor, +y
    quad({0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}); // ceiling, -y
    quad({0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}); // x = 0, +x
    quad({1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}); // x = 1, -x
    quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}); // z = 0, +z
    quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}); // z = 1, -z
    s.meshes.push_back(mesh);
    s.camera.position = glm::vec3(0.5f, 0.5f, 0.9f) * size;
    s.camera.forward = glm::normalize(glm::vec3(-0.3f, -0.2f, -1.0f));
    s.camera.up = glm::normalize(glm::cross(glm::cross(s.camera.forward, glm::vec3(0, 1, 0)), s.camera.forward));
    s.camera.yfovRad = 1.2f;
    s.camera.znear = 0.01f * size;
    s.camera.zfar = 10.0f * size;
    return s;
}

} // namespace bounce::testing
