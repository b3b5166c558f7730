// GPU ray casting against Embree on the same rays and scene, in rays per second (bounce rays, and the
// "rays" table of bounce bench). Coherent rays are the camera's primary rays of a square image;
// incoherent rays leave the surfaces those rays hit in cosine-distributed directions, as a final gather
// or a photon bounce does. Embree runs its single-ray queries (rtcIntersect1, as the path tracer does) on
// `threads` CPU threads; the GPU casts the same batch from a compute and from a fragment shader
// (gl/frame/ray_caster.h). On llvmpipe both run on the same CPU cores, so the ratio says how far the
// GLSL walk is from Embree's; on a GPU the GPU figures are the GPU's.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene.h"

namespace bounce::app {

struct RayThroughput {
    std::string kind; // "coherent" or "incoherent"
    std::size_t rays = 0;
    double embreeRaysPerS = 0.0, computeRaysPerS = 0.0, fragmentRaysPerS = 0.0;
    double agreement = 0.0;   // fraction of rays where the GPU (compute) and Embree found the same triangle
    double hitFraction = 0.0; // fraction of rays that hit anything (Embree)

    nlohmann::json toJson() const;
    static RayThroughput fromJson(const std::string& kind, const nlohmann::json& j); // toJson()'s inverse
};

// Coherent and incoherent figures for about `rays` rays (the nearest square), the median of `repeat`
// timed casts after one untimed one; threads 0: every core. Needs a current GL context.
std::vector<RayThroughput> measureRayThroughput(const core::Scene& scene, int rays, int repeat, int threads);

} // namespace bounce::app
