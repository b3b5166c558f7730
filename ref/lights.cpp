#include "ref/lights.h"

#include "core/brdf.h"

namespace bounce::ref {

LightTable::LightTable(const EmbreeScene& geometry)
{
    const core::Scene& scene = geometry.scene();
    emitterOfTriangle_.assign(geometry.triangleCount(), -1);
    std::vector<double> power;
    for (std::uint32_t t = 0; t < geometry.triangleCount(); ++t) {
        EmissiveTriangle e;
        std::uint32_t mesh = 0;
        geometry.triangle(t, e.p0, e.p1, e.p2, mesh);
        const core::Material& m = scene.materials[scene.meshes[mesh].material];
        if (!m.isEmissive()) continue;
        const glm::vec3 cross = glm::cross(e.p1 - e.p0, e.p2 - e.p0);
        e.area = 0.5f * glm::length(cross);
        if (!(e.area > 0.0f)) continue; // degenerate: never hit, never sampled
        e.ng = cross / (2.0f * e.area);
        e.radiance = m.emission;
        e.doubleSided = m.doubleSided;
        // Emitted flux of a Lambertian emitter: pi L A per face (luminance stands in for RGB).
        power.push_back(double(core::luminance(m.emission)) * double(e.area) * (e.doubleSided ? 2.0 : 1.0));
        emitterOfTriangle_[t] = int(emitters_.size());
        emitters_.push_back(e);
    }
    distribution_ = core::DiscreteDistribution(power);
}

AreaLightSample LightTable::sampleArea(float uSelect, const glm::vec2& uTri) const
{
    AreaLightSample s;
    if (distribution_.empty()) return s;
    const std::size_t i = distribution_.sample(uSelect);
    const EmissiveTriangle& e = emitters_[i];
    const glm::vec2 b = core::sampleUniformTriangle(uTri);
    s.p = b.x * e.p0 + b.y * e.p1 + (1.0f - b.x - b.y) * e.p2;
    s.ng = e.ng;
    s.radiance = e.radiance;
    s.pdfArea = distribution_.pmf(i) / e.area;
    s.doubleSided = e.doubleSided;
    return s;
}

float LightTable::pdfArea(std::uint32_t triangle) const
{
    if (triangle >= emitterOfTriangle_.size()) return 0.0f;
    const int i = emitterOfTriangle_[triangle];
    if (i < 0) return 0.0f;
    return distribution_.pmf(std::size_t(i)) / emitters_[std::size_t(i)].area;
}

glm::vec3 LightTable::emitted(const core::Material& m, const glm::vec3& ng, const glm::vec3& w)
{
    if (!m.isEmissive()) return glm::vec3(0.0f);
    const float c = glm::dot(ng, w);
    if (c > 0.0f || (m.doubleSided && c < 0.0f)) return m.emission;
    return glm::vec3(0.0f);
}

} // namespace bounce::ref
