// The closed-form pieces of importance-driven point projection (Maletz, Wang & Bowers 2011), CPU twins of
// glsl/technique/pointproj/pointproj.glsl (tests/core/point_projection_test.cpp). No GL here.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::core {

// Eq. 2, the hemi-octahedral map (Wang et al. 2006): w' = w / (|wx| + |wy| + |wz|), then
//   t_x = (1 - w'.x + w'.z) / 2,  t_y = (1 - w'.x - w'.z) / 2
// with the paper's y the normal. Here the local frame has z the normal (as everywhere in Bounce), so the
// paper's (x, y, z) is our (x, z, y): t = ((1 - w'.x + w'.y) / 2, (1 - w'.x - w'.y) / 2). The map takes the
// upper hemisphere one to one onto the unit square (the diamond |x'| + |y'| <= 1 turned by 45 degrees).
glm::vec2 hemiOctEncode(const glm::vec3& w);
glm::vec3 hemiOctDecode(const glm::vec2& t); // unit length, z >= 0

// The solid angle of every texel of an R x R hemi-octahedral buffer, row (t_y) major: each texel is four
// spherical triangles around its centre (the map is planar on each octant face, and the creases t_x = t_y,
// t_x + t_y = 1 run through texel centres and corners), each by Van Oosterom & Strackee's formula. They
// sum to 2 pi.
std::vector<float> hemiOctTexelSolidAngles(int resolution);

// Eq. 5, the robust solid angle of a disc of area A at distance d seen at cos theta_s from the shading
// point: 2 pi A cos / (A + 2 pi d^2). Never above 2 pi cos theta_s (the disc touching the point), ~ Eq. 3's
// A cos / d^2 far away.
float robustSolidAngle(float areaM2, float cosThetaS, float distance2);

// Eq. 1 / Eq. 4's per-point importance: max(cos theta_p, 0) |cos theta_s| / d^2 x dA (x f_r for Eq. 4).
float pointImportance(float cosThetaP, float cosThetaS, float distance2, float areaM2);

// §3.2's carry rule: integer sample counts n_k for the clusters, proportional to importance[k] (any
// non-negative scale: normalised here), from one uniform number per cluster (random[k] in [0,1)). Counts
// sum to exactly total: the last cluster takes what the float rounding of the carry left (at most one
// sample either way). All importances zero or non-finite: uniform, as the paper's random points (p_k = 1 /
// clusters).
std::vector<std::uint32_t> carryAllocate(const std::vector<float>& importance, std::uint32_t total,
                                         const std::vector<float>& random);

} // namespace bounce::core
