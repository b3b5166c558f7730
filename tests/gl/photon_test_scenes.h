// Scenes and helpers shared by the photon family's GL tests (tests/gl/photon_*_test.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "gl/frame/frame.h"

namespace bounce::photontest {

// A closed box [0, s]^3, inward-facing, every surface Lambertian with albedo rho, a point light of
// intensity I at its centre; the camera inside, looking at a corner.
inline core::Scene closedBox(float rho, float size = 1.0f, glm::vec3 intensity = glm::vec3(1.0f))
{
    core::Scene s;
    s.name = "closed box";
    core::Material m;
    m.name = "walls";
    m.baseColor = glm::vec3(rho);
    m.metallic = 0.0f;
    m.specular = 0.0f;
    s.materials.push_back(m);
    core::Mesh mesh;
    mesh.name = "box";
    const auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
        const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        const auto base = std::uint32_t(mesh.positions.size());
        for (const glm::vec3& p : {a, b, c, d}) {
            mesh.positions.push_back(p * size);
            mesh.normals.push_back(n);
        }
        for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
    };
    quad({0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0});
    quad({0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1});
    quad({0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1});
    quad({1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0});
    quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
    quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1});
    s.meshes.push_back(mesh);
    core::Light l;
    l.type = core::LightType::Point;
    l.position = glm::vec3(0.5f * size);
    l.intensity = intensity;
    s.lights.push_back(l);
    s.camera.position = glm::vec3(0.5f, 0.5f, 0.9f) * size;
    s.camera.forward = glm::normalize(glm::vec3(-0.3f, -0.2f, -1.0f));
    s.camera.up = glm::normalize(glm::cross(glm::cross(s.camera.forward, glm::vec3(0, 1, 0)), s.camera.forward));
    s.camera.yfovRad = 1.2f;
    s.camera.znear = 0.01f * size;
    s.camera.zfar = 10.0f * size;
    return s;
}

inline gl::FrameSettings smallFrame(int w, int h)
{
    gl::FrameSettings s;
    s.width = w;
    s.height = h;
    s.shadowMapSize = 256;
    return s;
}

} // namespace bounce::photontest
