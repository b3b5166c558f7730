// Contact shadows converge (issue 59): a box resting on a floor under a spot, the frame's still frames against
// the path tracer's direct light along the columns of pixels that run up the floor, across the box's shadow
// edge where it leaves the contact, and up the box's faces. With the still frames' shadow rays
// (shadow.still=rays, the default) every sample lies within 2% of the lit floor's value; with the shadow maps'
// shifted taps (shadow.still=maps) the map's normal offset and bias light a band along the contact that no
// count of frames removes (up to 78% of the lit floor here), and the same comparison fails.
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

constexpr int kSize = 64;

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
    // Close on the box's front corner: its lit +x face on the right, its shadowed +z face on the left, the
    // floor below them with the box's shadow edge running from the corner towards the camera.
    s.camera.position = {1.0f, 0.8f, 1.6f};
    s.camera.forward = glm::normalize(glm::vec3(h, 0.05f, h) - s.camera.position);
    s.camera.up = glm::normalize(glm::cross(glm::cross(s.camera.forward, glm::vec3(0, 1, 0)), s.camera.forward));
    s.camera.yfovRad = 0.3f;
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

// The largest difference along the columns that cross the box's shadow edge where it leaves the contact
// (the left half of the image's middle), each over its lit floor's value (the column's brightest reference
// sample).
double worstAcrossTheContact(const core::Image& image, const core::Image& reference)
{
    double worst = 0.0;
    for (int x = kSize / 4; x < kSize / 2; ++x) {
        double lit = 0.0;
        for (int y = 0; y < kSize; ++y) lit = std::max(lit, double(reference.at(x, y).y));
        for (int y = 0; y < kSize; ++y)
            worst = std::max(worst, std::abs(double(image.at(x, y).y) - double(reference.at(x, y).y)) / lit);
    }
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
    const double rays = worstAcrossTheContact(stillFrames(scene, "rays", 256), reference);
    const double maps = worstAcrossTheContact(stillFrames(scene, "maps", 256), reference);
    std::printf("[ measured ] largest difference across the contact over the lit floor: rays %.4f, maps %.4f\n", rays,
                maps);
    EXPECT_LT(rays, 0.02);
    EXPECT_GT(maps, 0.02) << "the maps' bias must show, or this test could not tell the rays from them";
}

} // namespace
} // namespace bounce
