// Contact shadows converge (issue 59): a box resting on a floor under a spot, the frame's still frames against
// the path tracer's direct light along a column of pixels that runs up the floor, across the contact line and
// up the box's shadowed face. With the still frames' shadow rays (shadow.still=rays, the default) every
// sample lies within 2% of the lit floor's value; with the shadow maps' shifted taps (shadow.still=maps) the
// map's bias lights a band along the contact that no count of frames removes, and the same comparison fails.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "core/image.h"
#include "core/scene.h"
#include "gl/renderer.h"
#include "gl/technique/technique.h"
#include "ref/reference.h"
#include "tests/gl/closed_box.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

constexpr int kSize = 32;

// A 4 m floor, a 0.5 m box on it at the origin, a spot above and behind the box (its shadow falls towards
// the camera's side, the contact in view), the camera low in front of the box's shadowed face.
core::Scene boxOnFloor()
{
    core::Scene s;
    core::Material white;
    white.name = "white";
    white.baseColor = glm::vec3(0.6f);
    white.specular = 0.0f;
    s.materials.push_back(white);
    core::Mesh floor;
    floor.name = "floor";
    testing::addQuad(floor, {-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2});
    s.meshes.push_back(floor);
    core::Mesh box;
    box.name = "box";
    const float h = 0.25f;
    const auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) { testing::addQuad(box, a, b, c, d); };
    quad({-h, 2 * h, -h}, {-h, 2 * h, h}, {h, 2 * h, h}, {h, 2 * h, -h}); // top, +y
    quad({-h, 0, h}, {h, 0, h}, {h, 2 * h, h}, {-h, 2 * h, h});           // +z face
    quad({-h, 0, -h}, {-h, 2 * h, -h}, {h, 2 * h, -h}, {h, 0, -h});       // -z face
    quad({h, 0, -h}, {h, 2 * h, -h}, {h, 2 * h, h}, {h, 0, h});           // +x face
    quad({-h, 0, -h}, {-h, 0, h}, {-h, 2 * h, h}, {-h, 2 * h, -h});       // -x face
    s.meshes.push_back(box);
    core::Light spot;
    spot.type = core::LightType::Spot;
    spot.position = {0.3f, 2.0f, -1.5f};
    spot.direction = glm::normalize(glm::vec3(0.0f, 0.0f, 0.6f) - spot.position);
    spot.intensity = glm::vec3(4.0f);
    spot.innerConeRad = 0.5f;
    spot.outerConeRad = 0.7f;
    s.lights.push_back(spot);
    s.camera.position = {0.1f, 0.35f, 1.4f};
    s.camera.forward = glm::normalize(glm::vec3(0.0f, 0.0f, h) - s.camera.position);
    s.camera.up = glm::normalize(glm::cross(glm::cross(s.camera.forward, glm::vec3(0, 1, 0)), s.camera.forward));
    s.camera.yfovRad = 0.5f;
    return s;
}

core::Image stillFrames(const core::Scene& scene, const std::string& shadows, int frames)
{
    gl::ParamValues v(gl::frameParams());
    v.set(gl::frameParams(), "shadow.still", shadows);
    gl::Renderer r(scene, "direct", v, gl::ParamValues(), kSize, kSize);
    for (int i = 0; i < frames; ++i) r.renderFrame();
    return r.image();
}

// The largest difference along the image's middle column, over the lit floor's value (the column's
// brightest reference sample).
double worstAlongTheColumn(const core::Image& image, const core::Image& reference, double& lit)
{
    const int x = kSize / 2;
    lit = 0.0;
    for (int y = 0; y < kSize; ++y) lit = std::max(lit, double(reference.at(x, y).y));
    double worst = 0.0;
    for (int y = 0; y < kSize; ++y)
        worst = std::max(worst, std::abs(double(image.at(x, y).y) - double(reference.at(x, y).y)) / lit);
    return worst;
}

class ContactShadowTest : public GlTest {};

TEST_F(ContactShadowTest, StillFramesConvergeToThePathTracerAcrossTheContact)
{
    const core::Scene scene = boxOnFloor();
    ref::RenderSettings rs;
    rs.paths = ref::LightPaths::Direct;
    rs.width = rs.height = kSize;
    rs.spp = 4096;
    rs.seed = 3;
    rs.progress = false;
    const core::Image reference = ref::render(scene, scene.camera, rs).image;
    double lit = 0.0;
    const double rays = worstAlongTheColumn(stillFrames(scene, "rays", 256), reference, lit);
    const double maps = worstAlongTheColumn(stillFrames(scene, "maps", 256), reference, lit);
    std::printf("[ measured ] largest difference along the column over the lit floor (%.4f): rays %.4f, maps %.4f\n",
                lit, rays, maps);
    ASSERT_GT(lit, 0.0);
    EXPECT_LT(rays, 0.02);
    EXPECT_GT(maps, 0.02) << "the maps' bias must show, or this test could not tell the rays from them";
}

} // namespace
} // namespace bounce
