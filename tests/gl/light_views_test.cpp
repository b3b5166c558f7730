// The sun's cascades (gl/frame/light_views.h): each one's rectangle in light space holds every point of the
// scene's box that its slice of the camera's frustum sees (found here by sampling, independently of the
// clipping that computes the rectangle), no more than the box itself; a frustum that misses the box gets no
// depth range; a directional light gets its cascades, then its view of the whole scene. CPU only.
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
