// The estimators of the reference: a unidirectional path tracer with next-event estimation, whose
// contributions are kept or dropped by the number of reflections they went through, and the
// "no visibility between x1 and x2" estimator of the one-bounce-without-visibility light paths.
// ref/README.md derives them.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/brdf.h"
#include "core/sampling.h"
#include "ref/embree_scene.h"
#include "ref/lights.h"
#include "ref/reference.h"

namespace bounce::ref {

class Integrator {
public:
    // maxDepth: the most reflections for LightPaths::Full (0: Russian roulette alone decides).
    Integrator(const EmbreeScene& geometry, const LightTable& lights, LightPaths paths, int maxDepth);

    // Radiance arriving at o from direction -d (d unit, pointing into the scene) over the selected light
    // paths. rays counts the Embree queries.
    glm::vec3 radiance(const glm::vec3& o, const glm::vec3& d, core::Pcg32& rng, std::uint64_t& rays) const;

private:
    // A hit prepared for shading, with both normals turned to the side the light leaves towards (wo).
    struct Shading {
        SurfacePoint surface;
        glm::vec3 n{0.0f};  // shading normal on wo's side
        glm::vec3 ng{0.0f}; // geometric normal on wo's side
        core::BrdfParams brdf;
        bool reflects = false; // some lobe has non-zero reflectance
    };

    // False for the back of a one-sided surface: it reflects and emits nothing (black).
    bool shade(const Hit& hit, const glm::vec3& wo, Shading& s) const;
    bool inRange(int reflections) const { return reflections >= minReflections_ && reflections <= maxReflections_; }

    // Next-event estimation at s: every punctual light, plus one area-light sample weighted for MIS
    // (power heuristic) against BRDF sampling.
    glm::vec3 lightSample(const Shading& s, const glm::vec3& wo, core::Pcg32& rng, std::uint64_t& rays) const;
    // The complete direct-light estimate at s (both MIS strategies); used at x2 by the no-visibility term.
    glm::vec3 directLight(const Shading& s, const glm::vec3& wo, core::Pcg32& rng, std::uint64_t& rays) const;
    // L(D|G){2}E with the x1-x2 visibility ignored, at x1 = s.
    glm::vec3 noVisibilityBounce(const Shading& s, const glm::vec3& wo, core::Pcg32& rng, std::uint64_t& rays) const;
    // The MIS weight of the BRDF strategy for a BRDF-sampled ray from `from` that hit emitter point p.
    float brdfHitWeight(float pdfBrdf, const glm::vec3& from, const SurfacePoint& p) const;

    const EmbreeScene& geometry_;
    const LightTable& lights_;
    int minReflections_ = 0;
    int maxReflections_ = 0;
    bool noVisibility_ = false;
    bool russianRoulette_ = false;
};

} // namespace bounce::ref
