// Moving frames' edge antialiasing (gl/frame/edge_antialias.h, frame parameter edgeAA) against a closed form:
// a lit square, turned in its plane so that no edge runs along the pixel grid, in front of a lit wall, both
// facing the camera and a directional light along the view. Each has one radiance (albedo / pi x 1 W/m^2),
// so a box-filtered pixel is the wall's radiance plus the difference times the area of the pixel the
// square's projection covers, computed here by clipping the projected square to each pixel. The frame
// samples pixel centres: without the antialiasing an edge pixel is one radiance or the other.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/image.h"
#include "core/scene.h"
#include "gl/renderer.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

constexpr float kSquareAlbedo = 0.8f;
constexpr float kWallAlbedo = 0.2f;

core::Mesh quad(const char* name, std::vector<glm::vec3> corners, std::uint32_t material,
                glm::vec3 normal = glm::vec3(0, 0, 1))
{
    core::Mesh m;
    m.name = name;
    m.positions = std::move(corners);
    m.normals.assign(4, normal);
    m.uvs.assign(4, glm::vec2(0.0f));
    m.indices = {0, 1, 2, 0, 2, 3};
    m.material = material;
    return m;
}

// The quad `m` (corners 0-3) as a grid of cells x cells quads, each split along its diagonal: edges inside
// one flat surface, which must not count as the surface's edges.
core::Mesh tessellated(const core::Mesh& m, int cells)
{
    core::Mesh out = m;
    out.positions.clear();
    out.indices.clear();
    const auto at = [&](float u, float v) {
        return (1 - u) * (1 - v) * m.positions[0] + u * (1 - v) * m.positions[1] + u * v * m.positions[2] +
               (1 - u) * v * m.positions[3];
    };
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) out.positions.push_back(at(float(i) / cells, float(j) / cells));
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            const std::uint32_t a = std::uint32_t(j * (cells + 1) + i), b = a + 1, c = b + std::uint32_t(cells + 1),
                                d = a + std::uint32_t(cells + 1);
            out.indices.insert(out.indices.end(), {a, b, c, a, c, d});
        }
    out.normals.assign(out.positions.size(), m.normals[0]);
    out.uvs.assign(out.positions.size(), glm::vec2(0.0f));
    return out;
}

// The square (half-side `half`, turned by `turn` radians about the view axis) at z = 0, the wall at z = -2
// (or none), the camera at z = 4 looking down -z, the light along the view.
core::Scene squareScene(float half, float turn, bool wall)
{
    core::Scene s;
    core::Material square;
    square.name = "square";
    square.baseColor = glm::vec3(kSquareAlbedo);
    square.specular = 0.0f;
    s.materials.push_back(square);
    core::Material back = square;
    back.name = "wall";
    back.baseColor = glm::vec3(kWallAlbedo);
    s.materials.push_back(back);
    std::vector<glm::vec3> corners;
    for (int i = 0; i < 4; ++i) {
        const float a = turn + float(i) * 0.5f * core::kPi + 0.25f * core::kPi;
        corners.push_back(glm::vec3(std::cos(a), std::sin(a), 0.0f) * (half * std::sqrt(2.0f)));
    }
    s.meshes.push_back(quad("square", corners, 0));
    if (wall) s.meshes.push_back(quad("wall", {{-9, -9, -2}, {9, -9, -2}, {9, 9, -2}, {-9, 9, -2}}, 1));
    core::Light sun;
    sun.type = core::LightType::Directional;
    sun.direction = glm::vec3(0.0f, 0.0f, -1.0f);
    sun.intensity = glm::vec3(1.0f);
    s.lights.push_back(sun);
    s.camera.position = {0.0f, 0.0f, 4.0f};
    s.camera.forward = {0.0f, 0.0f, -1.0f};
    s.camera.up = {0.0f, 1.0f, 0.0f};
    s.camera.yfovRad = 0.5f;
    return s;
}

// A floor at y = -0.5 that runs from behind the camera (its near corners at z = 5 and 6, the camera at z = 4)
// to a far edge turned against the image's rows, lit at 45 degrees: both its triangles cross the near plane.
core::Scene floorScene()
{
    core::Scene s = squareScene(0.6f, 0.0f, false);
    s.meshes[0] =
        quad("floor", {{-0.7f, -0.5f, 6.0f}, {0.9f, -0.5f, 5.0f}, {1.1f, -0.5f, -1.3f}, {-0.5f, -0.5f, -0.7f}}, 0,
             glm::vec3(0, 1, 0));
    s.lights[0].direction = glm::normalize(glm::vec3(0.0f, -1.0f, -1.0f));
    return s;
}

// A quad `outline` in window coordinates (y up, pixel i spans [i, i + 1]): clipped to the near plane in
// clip space (z >= -w), then projected.
std::vector<glm::dvec2> projectedQuad(const core::Scene& scene, const std::vector<glm::vec3>& outline, int width,
                                      int height)
{
    const glm::dmat4 viewProj(scene.camera.projection(float(width) / float(height)) * scene.camera.view());
    std::vector<glm::dvec4> clip, kept;
    for (const glm::vec3& p : outline) clip.push_back(viewProj * glm::dvec4(glm::dvec3(p), 1.0));
    for (std::size_t i = 0; i < clip.size(); ++i) {
        const glm::dvec4 a = clip[i], b = clip[(i + 1) % clip.size()];
        const double da = a.z + a.w, db = b.z + b.w;
        if (da >= 0.0) kept.push_back(a);
        if ((da >= 0.0) != (db >= 0.0)) kept.push_back(a + (b - a) * (da / (da - db)));
    }
    std::vector<glm::dvec2> poly;
    for (const glm::dvec4& c : kept)
        poly.push_back({(c.x / c.w * 0.5 + 0.5) * width, (c.y / c.w * 0.5 + 0.5) * height});
    return poly;
}

// The area of the convex polygon `poly` inside the pixel [x, x + 1] x [y, y + 1] (Sutherland-Hodgman, then
// the shoelace formula).
double coveredArea(std::vector<glm::dvec2> poly, double x, double y)
{
    const auto clip = [&](int axis, double bound, bool keepAbove) {
        std::vector<glm::dvec2> out;
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
            const bool ina = keepAbove ? a[axis] >= bound : a[axis] <= bound;
            const bool inb = keepAbove ? b[axis] >= bound : b[axis] <= bound;
            if (ina) out.push_back(a);
            if (ina != inb) out.push_back(a + (b - a) * ((bound - a[axis]) / (b[axis] - a[axis])));
        }
        poly = out;
    };
    clip(0, x, true);
    clip(0, x + 1, false);
    clip(1, y, true);
    clip(1, y + 1, false);
    double area = 0.0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        area += a.x * b.y - b.x * a.y;
    }
    return std::abs(area) * 0.5;
}

struct EdgeCheck {
    double worstEdge = 0.0;     // |render - closed form| / (near - far radiance), pixels one edge crosses
    double worstInterior = 0.0; // the same where the pixel is wholly one side
    int edgePixels = 0;
};

core::Image movingFrame(const core::Scene& scene, int width, int height, bool edgeAA)
{
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("edgeAA", edgeAA ? 1 : 0);
    frameValues.setValue("accumulate", 0);
    gl::Renderer r(scene, "direct", frameValues, gl::ParamValues(), width, height);
    r.renderFrame();
    return r.image();
}

// The quad `outline` (the first mesh's corners unless given), of radiance `near`, over a background of
// radiance `far`, against the closed form.
EdgeCheck check(const core::Scene& scene, const core::Image& image, double near, double far,
                std::vector<glm::vec3> outline = {})
{
    const int width = image.width, height = image.height;
    if (outline.empty()) outline = scene.meshes[0].positions;
    const std::vector<glm::dvec2> poly = projectedQuad(scene, outline, width, height);
    EdgeCheck out;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double covered = coveredArea(poly, x, y);
            const double expected = far + (near - far) * covered;
            const double got = image.at(x, height - 1 - y).x; // image row 0 is the top
            const double error = std::abs(got - expected) / std::abs(near - far);
            // Left out: pixels by a corner (two edges in one pixel: the nearest alone counts, and a line runs
            // on past its edge's end) and on the image's rim (the other side's light is a neighbour's, and
            // there may be none).
            bool nearCorner = false;
            for (const glm::dvec2& c : poly) nearCorner |= glm::length(c - glm::dvec2(x + 0.5, y + 0.5)) < 2.0;
            if (nearCorner || x == 0 || y == 0 || x == width - 1 || y == height - 1) continue;
            if (covered > 1e-9 && covered < 1.0 - 1e-9) {
                out.worstEdge = std::max(out.worstEdge, error);
                ++out.edgePixels;
            } else {
                out.worstInterior = std::max(out.worstInterior, error);
            }
        }
    return out;
}

class EdgeAntialiasTest : public GlTest {};

// Edges at 17 degrees to the grid, a viewport that is not a power of two: each edge pixel takes the area
// the square covers, both where the square's own triangle ends inside the pixel and where the square runs
// into a wall pixel from its neighbour. Against the black background (no geometry) and against a lit wall.
TEST_F(EdgeAntialiasTest, MovingFrameEdgePixelsTakeTheAreaEachSideCovers)
{
    for (const bool wall : {false, true}) {
        SCOPED_TRACE(wall ? "in front of a lit wall" : "against the background");
        const core::Scene scene = squareScene(0.6f, 17.0f * core::kPi / 180.0f, wall);
        const double square = kSquareAlbedo / core::kPi, background = wall ? kWallAlbedo / core::kPi : 0.0;
        const EdgeCheck centres = check(scene, movingFrame(scene, 45, 37, false), square, background);
        const EdgeCheck antialiased = check(scene, movingFrame(scene, 45, 37, true), square, background);
        EXPECT_GT(centres.edgePixels, 40);
        EXPECT_EQ(antialiased.edgePixels, centres.edgePixels);
        // Pixel centres: an edge pixel is off by up to its whole coverage.
        EXPECT_GT(centres.worstEdge, 0.4);
        EXPECT_LT(antialiased.worstEdge, 0.005);
        // Pixels wholly on one side keep their light (the frame's shading is within 1e-3 of the closed form
        // there, the same with and without).
        EXPECT_LT(centres.worstInterior, 1e-3);
        EXPECT_LE(antialiased.worstInterior, centres.worstInterior + 1e-6);
    }
}

// A surface that runs from behind the camera: its triangles' edges are lines on screen only through their
// visible parts (edges.geom takes the vertices as homogeneous points); the visible sides and far edge are
// antialiased as any edge, and no pixel inside it changes.
TEST_F(EdgeAntialiasTest, TrianglesCrossingTheNearPlaneKeepTheirVisibleEdges)
{
    const core::Scene scene = floorScene();
    const double floor = kSquareAlbedo / core::kPi * std::sqrt(0.5);
    const EdgeCheck centres = check(scene, movingFrame(scene, 40, 30, false), floor, 0.0);
    const EdgeCheck antialiased = check(scene, movingFrame(scene, 40, 30, true), floor, 0.0);
    EXPECT_GT(centres.edgePixels, 30);
    EXPECT_GT(centres.worstEdge, 0.4);
    EXPECT_LT(antialiased.worstEdge, 0.005);
    EXPECT_LT(centres.worstInterior, 1e-3);
    EXPECT_LE(antialiased.worstInterior, centres.worstInterior + 1e-6);
}

// The square made of 2 x 12 x 12 triangles, each a few pixels across: near its outline a pixel's nearest
// triangle edge is often one inside the square, which bounds nothing (the adjacency tells); the outline's
// pixels are antialiased as before.
TEST_F(EdgeAntialiasTest, EdgesInsideASurfaceAreNotItsEdges)
{
    core::Scene scene = squareScene(0.6f, 17.0f * core::kPi / 180.0f, false);
    const std::vector<glm::vec3> outline = scene.meshes[0].positions;
    scene.meshes[0] = tessellated(scene.meshes[0], 12);
    const double square = kSquareAlbedo / core::kPi;
    const EdgeCheck centres = check(scene, movingFrame(scene, 45, 37, false), square, 0.0, outline);
    const EdgeCheck antialiased = check(scene, movingFrame(scene, 45, 37, true), square, 0.0, outline);
    EXPECT_GT(centres.edgePixels, 40);
    EXPECT_GT(centres.worstEdge, 0.4);
    EXPECT_LT(antialiased.worstEdge, 0.005);
    EXPECT_LE(antialiased.worstInterior, centres.worstInterior + 1e-6);
}

// Still frames average jittered pixels, which converge to the box filter themselves: from the second frame
// of a still view on, the image is the same with the parameter on or off.
TEST_F(EdgeAntialiasTest, StillFramesAreLeftToTheirOwnAveraging)
{
    const core::Scene scene = squareScene(0.6f, 17.0f * core::kPi / 180.0f, true);
    std::vector<core::Image> images;
    for (const bool edgeAA : {false, true}) {
        gl::ParamValues frameValues(gl::frameParams());
        frameValues.setValue("edgeAA", edgeAA ? 1 : 0);
        gl::Renderer r(scene, "direct", frameValues, gl::ParamValues(), 45, 37);
        for (int i = 0; i < 4; ++i) r.renderFrame();
        EXPECT_EQ(r.stillFrames(), 3);
        images.push_back(r.image());
    }
    EXPECT_EQ(images[0].rgb, images[1].rgb);
}

} // namespace
} // namespace bounce
