// Deforming geometry in the tests (frame_test.cpp, microrender_test.cpp, pointproj_test.cpp,
// photon_technique_test.cpp): the vertices gl::Frame::moveVertices takes, and the moved scene as a loader
// gives it.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace bounce::testing {

// The scene's vertices scaled by `s` about the origin, in the order of gl::GpuScene's vertex buffer (the
// meshes in order), with normals transformed as normals are (the cofactor of diag(s), the inverse transpose
// up to its determinant, so that a zero scale flattens without dividing by zero; a normal it zeroes is kept):
// what gl::Frame::moveVertices takes to deform the scene.
struct MovedVertices {
    std::vector<glm::vec3> positions, normals;
};
inline MovedVertices scaledVertices(const core::Scene& scene, glm::vec3 s)
{
    MovedVertices v;
    for (const core::Mesh& m : scene.meshes)
        for (std::size_t i = 0; i < m.positions.size(); ++i) {
            v.positions.push_back(m.positions[i] * s);
            const glm::vec3 n = m.normals[i] * glm::vec3(s.y * s.z, s.x * s.z, s.x * s.y);
            v.normals.push_back(glm::dot(n, n) > 0.0f ? glm::normalize(n) : m.normals[i]);
        }
    return v;
}

// `scene` with its vertices replaced by `moved`'s (in the same order): the moved scene as a loader gives it.
inline core::Scene withVertices(core::Scene scene, const MovedVertices& moved)
{
    scene.setVertices(moved.positions, moved.normals);
    return scene;
}

// A scene and the same scene scaled by `s`: the vertices that deform the first into the second, and the
// second as a loader gives it (named NAME-stretched, so that its cached references are its own).
struct StretchedScene {
    core::Scene scene;
    MovedVertices moved;
    core::Scene stretched;
};
inline StretchedScene stretchedScene(const core::Scene& scene, glm::vec3 s)
{
    StretchedScene out{scene, scaledVertices(scene, s), {}};
    out.stretched = withVertices(scene, out.moved);
    out.stretched.name = scene.name + "-stretched";
    return out;
}

} // namespace bounce::testing
