// The direct light of a scene setup (core/scene_setup.h) from the OpenGL frame against the path tracer's
// `direct` on the same setup, and light through an alpha-masked quad in both.
//
// The setup is generated here, small enough for the test suite: a glTF written by the test holding one
// double-sided quad with glTF alphaMode MASK and a 4x4 RGBA texture, transparent on its left half
// (tests/alpha_mask_scene.h), and a setup file that adds a floor under it, a camera between the quad
// and the floor looking down (so the camera sees only the floor) and one light above the quad: the sun
// (an orthographic shadow map) or a spot (a perspective one). Under the transparent half the floor must
// be lit in both renderers, under the opaque half dark in both, and the two images must agree block by
// block (means over 8x8 pixels, which average out what the two do differently at an edge: pixel centres
// against the path tracer's box filter, shadow-map texels against exact shadow rays).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "core/gltf_io.h"
#include "core/image.h"
#include "core/scene_setup.h"
#include "gl/renderer.h"
#include "ref/reference.h"
#include "tests/alpha_mask_scene.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

constexpr int kSize = 64;
constexpr int kBlock = 8;
// Direct light from a sun or a spot has no noise where a pixel holds no edge; samples only resolve the
// edges.
constexpr int kReferenceSpp = 64;
// Block means, relative to the lit floor's mean. A shadow edge through a block changes at most one
// pixel per row (8 of 64) from pixel-centre to box-filtered coverage. Measured (llvmpipe, 2048^2 hard
// shadow map): sun 0.023 (a block on the quad's shadow edge at x = 0.5, which no pixel boundary
// follows), spot 0.00015 (its shadow edges lie outside the view or on a pixel boundary).
constexpr double kBlockTolerance = 0.05;

struct Case {
    const char* name;
    const char* light; // the setup's light, JSON
};
const Case kCases[] = {
    {"sun", R"({"type": "directional", "direction": [0, -1, 0], "irradiance": 3})"},
    {"spot", R"({"type": "spot", "position": [0, 2.5, 0], "direction": [0, -1, 0], "intensity": 10, "outerDeg": 50})"},
};

void PrintTo(const Case& c, std::ostream* os)
{
    *os << c.name;
}

fs::path outDir(const std::string& name)
{
    const fs::path d = fs::path(BOUNCE_TEST_OUT) / "gl" / "setup-direct" / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

// Writes the masked quad as glTF and a setup around it; returns the setup's path.
fs::path writeSetup(const Case& c)
{
    const fs::path d = outDir(c.name);
    core::Scene quad;
    testing::addMaskedQuad(quad);
    core::writeGltf(quad, (d / "mask.gltf").string());
    std::ofstream(d / "setup.json") << R"({
  "gltf": "mask.gltf",
  "floor": {"y": 0, "halfSize": 1, "albedo": [0.5, 0.5, 0.5]},
  "camera": {"position": [0, 1.2, 0], "forward": [0, -1, 0], "up": [0, 0, -1], "yfovDeg": 60},
  "lights": [)" << c.light << "]\n}\n";
    return d / "setup.json";
}

core::Image renderGl(const core::Scene& scene)
{
    gl::ParamValues frameValues(gl::frameParams());
    frameValues.setValue("shadow.size", 2048);
    frameValues.setValue("shadow.pcf", 0); // the path tracer's shadows are hard
    frameValues.setValue("shadow.linear", 0);
    gl::Renderer r(scene, "direct", frameValues, gl::ParamValues(), kSize, kSize);
    r.renderFrame();
    return r.image();
}

core::Image renderReference(const core::Scene& scene)
{
    ref::RenderSettings s;
    s.paths = ref::LightPaths::Direct;
    s.width = s.height = kSize;
    s.spp = kReferenceSpp;
    s.seed = 5;
    s.progress = false;
    const ref::RenderResult r = ref::render(scene, scene.camera, s);
    EXPECT_EQ(r.nonFiniteSamples, 0u);
    return r.image;
}

// Mean green radiance over the floor under the transparent half (x < 0) and the opaque half (x > 0) of
// the quad, 6 cm or more away from the quad's edges and its seam.
struct Regions {
    double hole = 0.0, opaque = 0.0;
};
Regions regions(const core::Image& im, const core::Camera& camera)
{
    Regions r;
    int holeCount = 0, opaqueCount = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec3 d = camera.rayDirection(x + 0.5f, y + 0.5f, kSize, kSize);
            const glm::vec3 p = camera.position + d * (camera.position.y / -d.y);
            if (std::abs(p.z) > 0.4f || std::abs(p.x) < 0.06f || std::abs(p.x) > 0.44f) continue;
            (p.x < 0.0f ? r.hole : r.opaque) += im.at(x, y).y;
            ++(p.x < 0.0f ? holeCount : opaqueCount);
        }
    EXPECT_GT(holeCount, 100);
    EXPECT_GT(opaqueCount, 100);
    r.hole /= std::max(holeCount, 1);
    r.opaque /= std::max(opaqueCount, 1);
    return r;
}

// The largest difference of 8x8 block means (all channels), and where.
double worstBlock(const core::Image& a, const core::Image& b, int& bx, int& by)
{
    double worst = 0.0;
    for (int y0 = 0; y0 < kSize; y0 += kBlock)
        for (int x0 = 0; x0 < kSize; x0 += kBlock) {
            glm::dvec3 sa(0.0), sb(0.0);
            for (int y = y0; y < y0 + kBlock; ++y)
                for (int x = x0; x < x0 + kBlock; ++x) {
                    sa += glm::dvec3(a.at(x, y));
                    sb += glm::dvec3(b.at(x, y));
                }
            const glm::dvec3 diff = glm::abs(sa - sb) / double(kBlock * kBlock);
            const double m = std::max({diff.x, diff.y, diff.z});
            if (m > worst) {
                worst = m;
                bx = x0 / kBlock;
                by = y0 / kBlock;
            }
        }
    return worst;
}

class SetupDirectTest : public GlTest, public ::testing::WithParamInterface<Case> {};

TEST_P(SetupDirectTest, GlDirectMatchesPathTracerThroughAnAlphaMask)
{
    const core::Scene scene = core::loadSetup(writeSetup(GetParam()).string());
    ASSERT_TRUE(scene.hasAlphaMask()); // the glTF carried the mask
    const core::Image gl = renderGl(scene);
    const core::Image pt = renderReference(scene);
    core::writeImage((fs::path(BOUNCE_TEST_OUT) / "gl" / "setup-direct" / GetParam().name / "gl.exr").string(), gl);
    core::writeImage((fs::path(BOUNCE_TEST_OUT) / "gl" / "setup-direct" / GetParam().name / "pt.exr").string(), pt);

    const Regions g = regions(gl, scene.camera), p = regions(pt, scene.camera);
    std::printf("[ measured ] %s: under the hole GL %.5g, path tracer %.5g; under the opaque half GL %.3g, path "
                "tracer %.3g\n",
                GetParam().name, g.hole, p.hole, g.opaque, p.opaque);
    // Light passes the transparent half in both, the opaque half stops it in both.
    EXPECT_GT(p.hole, 0.05);
    EXPECT_NEAR(g.hole, p.hole, 0.01 * p.hole); // half-float G-buffer
    EXPECT_LT(g.opaque, 1e-3 * p.hole);
    EXPECT_LT(p.opaque, 1e-3 * p.hole);

    int bx = 0, by = 0;
    const double worst = worstBlock(gl, pt, bx, by) / p.hole;
    std::printf("[ measured ] %s: worst 8x8 block differs by %.4g of the lit floor (block %d, %d)\n", GetParam().name,
                worst, bx, by);
    EXPECT_LE(worst, kBlockTolerance) << "block " << bx << ", " << by;
}

INSTANTIATE_TEST_SUITE_P(Lights, SetupDirectTest, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& i) { return std::string(i.param.name); });

} // namespace
} // namespace bounce
