// A brute-force CPU ray caster over a core::Scene, independent of both the GL renderer and the Embree
// path tracer, for tests that ask "what does this pixel see" and "is this point lit".
#pragma once

#include <cmath>
#include <limits>
#include <optional>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace bounce::test {

struct Hit {
    float t = std::numeric_limits<float>::infinity();
    glm::vec3 position{0.0f};
    glm::vec3 geometricNormal{0.0f}; // of the triangle, by its winding
    std::uint32_t material = 0;
    std::size_t mesh = 0;
};

// Möller-Trumbore, both sides (every surface blocks light from both sides).
inline std::optional<Hit> raycast(const core::Scene& scene, const glm::vec3& o, const glm::vec3& d,
                                  float tMax = std::numeric_limits<float>::infinity())
{
    Hit best;
    best.t = tMax;
    bool found = false;
    for (std::size_t mi = 0; mi < scene.meshes.size(); ++mi) {
        const core::Mesh& m = scene.meshes[mi];
        for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
            const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                            c = m.positions[m.indices[i + 2]];
            const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
            const float det = glm::dot(e1, p);
            if (std::abs(det) < 1e-12f) continue;
            const float inv = 1.0f / det;
            const glm::vec3 s = o - a;
            const float u = glm::dot(s, p) * inv;
            if (u < 0.0f || u > 1.0f) continue;
            const glm::vec3 q = glm::cross(s, e1);
            const float v = glm::dot(d, q) * inv;
            if (v < 0.0f || u + v > 1.0f) continue;
            const float t = glm::dot(e2, q) * inv;
            if (t > 1e-6f && t < best.t) {
                best.t = t;
                best.position = o + t * d;
                best.geometricNormal = glm::normalize(glm::cross(e1, e2));
                best.material = m.material;
                best.mesh = mi;
                found = true;
            }
        }
    }
    if (!found) return std::nullopt;
    return best;
}

// True when nothing lies strictly between p (nudged along n) and the point light at l.
inline bool visible(const core::Scene& scene, const glm::vec3& p, const glm::vec3& n, const glm::vec3& l)
{
    const glm::vec3 o = p + n * 1e-4f;
    const glm::vec3 d = l - o;
    const float dist = glm::length(d);
    return !raycast(scene, o, d / dist, dist * (1.0f - 1e-4f));
}

} // namespace bounce::test
