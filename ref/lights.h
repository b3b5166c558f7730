// What the path tracer samples light from: the scene's punctual lights (each one every time: scenes
// have few) and its emissive triangles (one per sample, chosen in proportion to emitted power and
// then uniformly by area).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/sampling.h"
#include "ref/embree_scene.h"

namespace bounce::ref {

struct EmissiveTriangle {
    glm::vec3 p0{0.0f}, p1{0.0f}, p2{0.0f};
    glm::vec3 ng{0.0f, 0.0f, 1.0f}; // front (counter-clockwise) side
    float area = 0.0f;
    glm::vec3 radiance{0.0f}; // W/(m^2 sr), constant over the triangle
    bool doubleSided = false; // emits from both faces
};

struct AreaLightSample {
    glm::vec3 p{0.0f};
    glm::vec3 ng{0.0f}; // the geometric normal of the triangle as stored
    glm::vec3 radiance{0.0f};
    float pdfArea = 0.0f; // selection probability / area, per square metre
    bool doubleSided = false;
};

class LightTable {
public:
    explicit LightTable(const EmbreeScene& geometry);

    bool hasAreaLights() const { return !distribution_.empty(); }
    // A point on an emissive triangle; uSelect picks the triangle (power-proportional), uTri the point.
    AreaLightSample sampleArea(float uSelect, const glm::vec2& uTri) const;
    // The area density with which sampleArea produces a point on global triangle `triangle`: 0 for
    // triangles that do not emit.
    float pdfArea(std::uint32_t triangle) const;
    const std::vector<EmissiveTriangle>& emitters() const { return emitters_; }

    // Radiance leaving an emitter at a point with geometric normal ng towards direction w (unit,
    // pointing away from the surface): the front face emits, the back only when double-sided.
    static glm::vec3 emitted(const core::Material& m, const glm::vec3& ng, const glm::vec3& w);

private:
    std::vector<EmissiveTriangle> emitters_;
    std::vector<int> emitterOfTriangle_; // global triangle -> index into emitters_, or -1
    core::DiscreteDistribution distribution_;
};

} // namespace bounce::ref
