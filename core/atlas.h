// A texture atlas over every surface of a scene: the parameterisation global ray-bundles (Hermes et al.
// 2010, Sec. 4.1) store position, normal, material and radiance in. No GL here.
//
// The method (buildAtlas):
//   1. Charts by region growing: triangles are welded by position, and a chart grows from its first
//      unassigned triangle over manifold edges (shared by exactly two triangles: where more meet, as
//      under a wall between two floors, the sides stay apart) to every triangle whose face normal lies within
//      AtlasSettings::maxNormalAngleRad of the seed's. Degenerate triangles join the chart that reaches
//      them (or seed one of their own).
//   2. Each chart is projected orthographically onto the plane of its seed normal and scaled by the texel
//      density (texels per metre), so a texel covers about 1/density^2 m^2 (divided by the cosine
//      between a triangle's normal and the chart's, at most maxNormalAngleRad apart).
//   3. Charts are packed by shelves, tallest first, into an atlas about as wide as it is tall, each with a
//      gutter of AtlasSettings::gutter texels on every side, so that the filled border of one chart
//      (below) never reaches the next.
// Atlas coordinates are in texels: texel (i, j) covers [i, i+1) x [j, j+1), its centre at (i + 0.5,
// j + 0.5). A triangle "touches" a texel when the texel's square and the triangle meet.
//
// Filling (for the GPU's rasterisation into the atlas, which has no conservative mode on llvmpipe): a
// triangle fills every texel whose centre lies within kFillMargin texels (Euclidean) of it. That holds
// every texel it touches and every texel a bilinear lookup anywhere inside it reads (centres within
// Chebyshev distance 1 of the triangle, so within sqrt(2)). The GPU rasterises fillQuad (the triangle's
// bounding box grown by the margin) and keeps the fragments fillsTexel keeps; a texel filled by several
// triangles belongs to the nearest (the one containing its centre first).
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace bounce::core {

struct AtlasError : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

// Texels whose centre lies within this distance (texels) of a triangle are filled with its data.
inline constexpr float kFillMargin = 1.4142136f + 0.01f;

struct AtlasSettings {
    float texelsPerMetre = 64.0f;
    int gutter = 2;                       // texels on every side of a chart (at least 2)
    float maxNormalAngleRad = 0.2617994f; // 15 degrees: region growing stops at sharper creases
    int maxSize = 16384;                  // refuse atlases wider or taller than this
};

struct AtlasChart {
    glm::ivec2 origin{0}; // lower-left texel of the chart's rectangle, gutter included
    glm::ivec2 size{0};   // the rectangle's size in texels, gutter included
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    glm::vec3 axisU{1.0f, 0.0f, 0.0f}, axisV{0.0f, 1.0f, 0.0f}; // the projection plane's axes
    std::uint32_t firstTriangle = 0;                            // the seed (global triangle index)
    std::uint32_t triangleCount = 0;
};

struct Atlas {
    int width = 0, height = 0;
    float texelsPerMetre = 0.0f;
    int gutter = 0;
    double surfaceAreaM2 = 0.0;
    std::vector<AtlasChart> charts;
    // Per global triangle (meshes in order, as GpuScene uploads them): its chart and its three corners in
    // atlas coordinates (texels), in the order of the mesh's indices.
    std::vector<std::uint32_t> triangleChart;
    std::vector<std::array<glm::vec2, 3>> corners;

    std::size_t triangleCount() const { return triangleChart.size(); }
    // The chart's rectangle without its gutter: where its triangles' touched texels lie.
    glm::ivec4 interior(std::uint32_t chart) const; // x0, y0, x1, y1 (exclusive)
};

// Texels per metre so that the charts' surface covers about `texels` texels.
float texelsPerMetreFor(const Scene& scene, double texels);
double surfaceArea(const Scene& scene);

// Throws AtlasError when the scene has no triangle, the density is not positive and finite, or the
// atlas would exceed settings.maxSize.
Atlas buildAtlas(const Scene& scene, const AtlasSettings& settings);

// Distance (texels) from point q to the triangle (0 inside).
float distanceToTriangle(const std::array<glm::vec2, 3>& t, glm::vec2 q);
// The triangle's bounding box grown by `margin`: x0, y0, x1, y1 (what the filling pass rasterises).
glm::vec4 fillQuad(const std::array<glm::vec2, 3>& t, float margin = kFillMargin);
// Whether the filling pass gives texel (i, j) the triangle's data.
bool fillsTexel(const std::array<glm::vec2, 3>& t, int i, int j, float margin = kFillMargin);

// Whether texel (i, j)'s square meets the triangle (separating axes: the square's two and the
// triangle's three edge normals).
bool texelTouches(const std::array<glm::vec2, 3>& t, int i, int j);
// Every texel the triangle touches.
std::vector<glm::ivec2> touchedTexels(const std::array<glm::vec2, 3>& t);

} // namespace bounce::core
