// The sun's cascades (gl/frame/light_views.h): each one's rectangle in light space holds every point of the
// scene's box that its slice of the camera's frustum sees (found here by sampling, independently of the
// clipping that computes the rectangle), no more than the box itself; a frustum that misses the box gets no
// depth range; a directional light gets its cascades, then its view of the whole scene. A spot's footprint
// side (footprintSide) against the closed forms of a spot that sees what the camera sees. CPU only.
#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "gl/frame/light_views.h"

namespace bounce {
namespace {

core::Bounds unitBox()
{
    core::Bounds b;
    b.extend({-1.0f, 0.0f, -2.0f});
    b.extend({3.0f, 2.0f, 1.0f});
    return b;
}

gl::ViewFit fitFrom(glm::vec3 position, glm::vec3 target, int cascades)
{
    gl::ViewFit f;
    f.camera.position = position;
    f.camera.forward = glm::normalize(target - position);
    f.camera.up = glm::normalize(glm::cross(glm::cross(f.camera.forward, glm::vec3(0, 1, 0)), f.camera.forward));
    f.camera.yfovRad = 0.9f;
    f.camera.znear = 0.05f;
    f.aspect = 1.5f;
    f.cascades = cascades;
    return f;
}

// Whether p lies in the camera's frustum between view distances d0 and d1.
bool inSlice(const gl::ViewFit& f, glm::vec3 p, float d0, float d1)
{
    const glm::vec3 v = p - f.camera.position;
    const float d = glm::dot(v, f.camera.forward);
    if (d < d0 || d > d1) return false;
    const glm::vec3 right = glm::normalize(glm::cross(f.camera.forward, f.camera.up));
    const float ty = std::tan(0.5f * f.camera.yfovRad);
    return std::abs(glm::dot(v, f.camera.up)) <= d * ty && std::abs(glm::dot(v, right)) <= d * ty * f.aspect;
}

TEST(LightViews, CascadeRectanglesHoldWhatTheirSlicesSee)
{
    const core::Bounds box = unitBox();
    const glm::vec3 sunDir = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    const glm::mat4 lightView = glm::lookAt(box.centre() - 10.0f * sunDir, box.centre(), gl::lightUpVector(sunDir));
    // From outside the box looking in, and from inside it at a corner (the near plane inside the box).
    for (const gl::ViewFit& f :
         {fitFrom({-4.0f, 1.5f, 3.0f}, {1.0f, 1.0f, -0.5f}, 3), fitFrom({-0.9f, 0.2f, -1.9f}, {3.0f, 1.0f, 1.0f}, 3)}) {
        const glm::vec2 depths = gl::viewDepthRange(f, box);
        ASSERT_GT(depths.y, depths.x);
        EXPECT_GE(depths.x, f.camera.znear);
        glm::vec4 boxRect(1e30f, 1e30f, -1e30f, -1e30f);
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 c(i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y, i & 4 ? box.hi.z : box.lo.z);
            const glm::vec2 q(lightView * glm::vec4(c, 1.0f));
            boxRect = glm::vec4(glm::min(glm::vec2(boxRect), q), glm::max(glm::vec2(boxRect.z, boxRect.w), q));
        }
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        for (int k = 0; k < f.cascades; ++k) {
            const float d0 = gl::cascadeSplit(depths.x, depths.y, k, f.cascades);
            const float d1 = gl::cascadeSplit(depths.x, depths.y, k + 1, f.cascades);
            EXPECT_LT(d0, d1);
            glm::vec4 rect;
            ASSERT_TRUE(gl::sliceLightRect(f, d0, d1, box, lightView, rect)) << "cascade " << k;
            EXPECT_GE(rect.x, boxRect.x - 1e-4f);
            EXPECT_GE(rect.y, boxRect.y - 1e-4f);
            EXPECT_LE(rect.z, boxRect.z + 1e-4f);
            EXPECT_LE(rect.w, boxRect.w + 1e-4f);
            int seen = 0;
            for (int n = 0; n < 20000; ++n) {
                const glm::vec3 p = box.lo + glm::vec3(u(rng), u(rng), u(rng)) * box.extent();
                if (!inSlice(f, p, d0, d1)) continue;
                ++seen;
                const glm::vec2 q(lightView * glm::vec4(p, 1.0f));
                EXPECT_TRUE(q.x >= rect.x - 1e-4f && q.x <= rect.z + 1e-4f && q.y >= rect.y - 1e-4f &&
                            q.y <= rect.w + 1e-4f)
                    << "cascade " << k << ": a point its slice sees lies outside its rectangle";
            }
            EXPECT_GT(seen, 0) << "cascade " << k;
        }
        EXPECT_NEAR(gl::cascadeSplit(depths.x, depths.y, 0, 3), depths.x, 1e-5f);
        EXPECT_NEAR(gl::cascadeSplit(depths.x, depths.y, 3, 3), depths.y, 1e-4f * depths.y);
    }
}

TEST(LightViews, FrustumThatMissesTheBoxHasNoDepthRange)
{
    const gl::ViewFit away = fitFrom({-4.0f, 1.0f, 0.0f}, {-8.0f, 1.0f, 0.0f}, 3);
    EXPECT_EQ(gl::viewDepthRange(away, unitBox()), glm::vec2(0.0f));
}

// A spot at the camera's eye, looking where it looks with a square field of view fovRad, its one view.
gl::LightView spotAtTheEye(const gl::ViewFit& f, float fovRad, const core::Bounds& b)
{
    gl::LightSource spot;
    spot.type = gl::kLightSpot;
    spot.position = f.camera.position;
    spot.direction = f.camera.forward;
    spot.outerConeRad = 0.5f * fovRad;
    const gl::LightViews lv = gl::buildLightViews({spot}, b);
    EXPECT_EQ(lv.views.size(), 1u);
    return lv.views.at(0);
}

gl::ViewFit squareCamera(glm::vec3 position, glm::vec3 target, float fovRad)
{
    gl::ViewFit f = fitFrom(position, target, 0);
    f.camera.yfovRad = fovRad;
    f.aspect = 1.0f;
    return f;
}

// A spot that sees exactly what the camera sees maps the region onto the same share of its view as of the
// screen: its side is the image's height, whatever the region (here a box the frustum cuts at its sides),
// with a viewport that is not a power of two.
TEST(LightViews, FootprintOfASpotAtTheEyeIsTheImageHeight)
{
    const gl::ViewFit f = squareCamera({-3.0f, 1.0f, 0.5f}, {1.0f, 0.8f, -0.5f}, 0.9f);
    const gl::LightView v = spotAtTheEye(f, 0.9f, unitBox());
    EXPECT_NEAR(gl::footprintSide(v, f, 77, unitBox()), 77.0f, 0.01f);
    EXPECT_NEAR(gl::footprintSide(v, f, 1000, unitBox()), 1000.0f, 0.1f);
}

// The camera inside a large box sees all of its frustum; a spot at the eye twice as wide covers the camera's
// view with the share tan(fov_c / 2) / tan(fov_l / 2) of its side: it needs that much more side.
TEST(LightViews, FootprintOfAWiderSpotGrowsWithItsShareOfTheView)
{
    core::Bounds room;
    room.extend(glm::vec3(-50.0f));
    room.extend(glm::vec3(50.0f));
    const gl::ViewFit f = squareCamera({0.0f, 1.0f, 0.0f}, {4.0f, 1.5f, 1.0f}, 0.5f);
    const gl::LightView v = spotAtTheEye(f, 1.0f, room);
    const float expected = 256.0f * std::tan(0.5f) / std::tan(0.25f);
    EXPECT_NEAR(gl::footprintSide(v, f, 256, room), expected, 1e-3f * expected);
}

// Hard cases: a spot facing away from what the camera sees needs nothing; a scene scaled by 1e4 or 1e-3
// (camera, spot and box together) needs the same side; a camera with NaN in it sees nothing; a flat scene
// (a floor of zero thickness) is seen as a thick one.
TEST(LightViews, FootprintHardCases)
{
    const gl::ViewFit f = squareCamera({-3.0f, 1.0f, 0.5f}, {1.0f, 0.8f, -0.5f}, 0.9f);
    gl::ViewFit back = f;
    back.camera.forward = -f.camera.forward;
    EXPECT_EQ(gl::footprintSide(spotAtTheEye(back, 0.9f, unitBox()), f, 256, unitBox()), 0.0f);

    const gl::ViewFit near = squareCamera({-0.5f, 1.0f, 0.5f}, {1.0f, 0.8f, -0.5f}, 0.6f);
    const gl::LightView wide = spotAtTheEye(near, 1.2f, unitBox());
    const float side = gl::footprintSide(wide, near, 256, unitBox());
    EXPECT_GT(side, 256.0f);
    for (float k : {1e4f, 1e-3f}) {
        gl::ViewFit scaled = near;
        scaled.camera.position *= k;
        scaled.camera.znear *= k;
        scaled.camera.zfar *= k;
        core::Bounds box;
        box.extend(unitBox().lo * k);
        box.extend(unitBox().hi * k);
        EXPECT_NEAR(gl::footprintSide(spotAtTheEye(scaled, 1.2f, box), scaled, 256, box), side, 1e-3f * side) << k;
    }

    gl::ViewFit lost = near;
    lost.camera.position.x = std::nanf("");
    EXPECT_EQ(gl::footprintSide(wide, lost, 256, unitBox()), 0.0f) << "NaN in the camera: no region";

    core::Bounds floor;
    floor.extend({-2.0f, 0.0f, -2.0f});
    floor.extend({2.0f, 0.0f, 2.0f});
    const gl::ViewFit above = squareCamera({0.0f, 3.0f, 0.0f}, {0.6f, 0.0f, 0.3f}, 0.7f);
    EXPECT_NEAR(gl::footprintSide(spotAtTheEye(above, 0.7f, floor), above, 100, floor), 100.0f, 0.01f);
}

TEST(LightViews, SunGetsItsCascadesThenTheWholeScene)
{
    gl::LightSource sun;
    sun.type = gl::kLightDirectional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    gl::LightViewOptions o;
    o.fit = fitFrom({-4.0f, 1.5f, 3.0f}, {1.0f, 1.0f, -0.5f}, 3);
    const gl::LightViews lv = gl::buildLightViews({sun}, unitBox(), o);
    ASSERT_EQ(lv.views.size(), 4u);
    EXPECT_EQ(lv.lightViews[0], glm::ivec2(0, 4));
    for (int i = 0; i < 3; ++i) {
        EXPECT_TRUE(lv.views[std::size_t(i)].cascade) << i;
        // Finer than the whole-scene view.
        EXPECT_LT(lv.views[std::size_t(i)].orthoHalfExtent, lv.views[3].orthoHalfExtent) << i;
    }
    EXPECT_FALSE(lv.views[3].cascade);
    EXPECT_EQ(gl::buildLightViews({sun}, unitBox()).views.size(), 1u) << "no camera to fit: the whole scene only";
}

} // namespace
} // namespace bounce
