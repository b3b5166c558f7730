// Blue-noise points over a scene's surfaces: the point clouds of point-based final gathering
// (micro-rendering, Ritschel et al. 2009; importance-driven point projection, Maletz et al. 2011)
// and of any CPU-side surface sampler. No GL here.
//
// Each point is stored as (triangle, barycentrics) in the scene's global triangle order (meshes in
// order, triangles in order within a mesh: the order GpuScene uploads them in), not as a position, so
// the cloud follows the geometry when the scene's vertices move; evaluateSurfacePoint turns it into a
// world position and normal for the scene as it is now.
//
// The method (sampleSurfacePoints):
//   1. kCandidatesPerPoint x N candidates, uniform by area (triangle chosen with probability
//      proportional to its area, then the square-root warp of sampling.h).
//      A candidate in a hole of an alpha mask (glTF MASK, core/texture_sampling.h) is drawn again, and
//      A below is the opaque area: the total times the share of draws that landed outside the holes.
//   2. Dart throwing over the candidates in their (random) order with the hard radius
//      r = kMinDistanceFactor * sqrt(A / N), distances in 3D (what a splat or a gather sees), so the
//      points stay apart across edges too. If fewer than N darts land (tiny N, a few large
//      triangles), r shrinks by 20% and the throw restarts; SurfacePoints::minDistance says which r
//      held.
//   3. Weighted sample elimination (Yuksel 2015, "Sample Elimination for Generating Poisson Disk
//      Sample Sets", Eq. 1 with alpha = 8 and r_max of Eq. 5, the hexagonal-packing radius
//      sqrt(A / (2 sqrt(3) N))) removes the surplus darts down to exactly N, the most crowded first.
//      Any subset of an r-separated set is r-separated: the guarantee of step 2 survives.
// Guarantee: every two points are at least SurfacePoints::minDistance apart (3D), and when no restart
// was needed minDistance == kMinDistanceFactor * sqrt(A / N). For reference, random sequential
// adsorption jams at a coverage of 0.547 (Feder 1980), i.e. near c = 0.83 with unlimited candidates.
// From 5N candidates, c = 0.65 lands 1.10-1.12 N darts on the Cornell box for N from 100 to 20000
// (c = 0.7 landed 0.97-0.99 N: too tight), which leaves step 3 a tenth to remove.
//
// Every point carries the area A / N (the uniform share, not a Voronoi cell): the areas sum to the
// total area exactly up to rounding, and the density of the points is A / N in expectation.
// Deterministic from the seed: same scene, count and seed give the same points on every machine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace bounce::core {

inline constexpr int kCandidatesPerPoint = 5;      // Yuksel 2015 recommends 5x the output count
inline constexpr float kMinDistanceFactor = 0.65f; // r = c sqrt(A / N) of step 2

struct SurfacePointError : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

struct SurfacePoint {
    std::uint32_t triangle = 0;   // global triangle index (meshes in order, triangles in order)
    glm::vec2 barycentrics{0.0f}; // (b0, b1): p = b0 p0 + b1 p1 + (1 - b0 - b1) p2, as sampleUniformTriangle
    float areaM2 = 0.0f;          // the point's share of the surface: total area / N
};

struct SurfacePoints {
    std::vector<SurfacePoint> points;
    double totalAreaM2 = 0.0; // the scene's surface area (degenerate triangles add nothing; alpha masks' holes
                              // left out, estimated from the candidates' draws)
    double minDistance = 0.0; // every two points are at least this far apart (metres, 3D)
    int restarts = 0;         // radius reductions of step 2 (0 on ordinary scenes)
};

// N points over `scene`'s triangles. Zero-area triangles get no points. Throws SurfacePointError when
// the scene is invalid (NaN/Inf positions, indices out of range: Scene::validate's message) or has no
// area while count > 0. count == 0 gives no points.
SurfacePoints sampleSurfacePoints(const Scene& scene, std::size_t count, std::uint64_t seed);

struct SurfaceSample {
    glm::vec3 position{0.0f};        // world space, metres
    glm::vec3 normal{0.0f};          // the mesh's vertex normals interpolated, unit length
    glm::vec3 geometricNormal{0.0f}; // the triangle's face normal (counter-clockwise front), unit length
};

// World position and normals of points for the scene as it is now. Throws SurfacePointError when a
// triangle index is outside the scene.
SurfaceSample evaluateSurfacePoint(const Scene& scene, const SurfacePoint& point);
std::vector<SurfaceSample> evaluateSurfacePoints(const Scene& scene, const std::vector<SurfacePoint>& points);

// The area of every triangle in the global order (metres^2, computed in double): what step 1 samples.
std::vector<double> triangleAreas(const Scene& scene);

} // namespace bounce::core
