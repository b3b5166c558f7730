// The views a light is seen from, shared by every map rendered from the lights (shadow maps, reflective
// shadow maps): a spot with a narrow enough cone gets one perspective view, a directional light one
// orthographic view fitted to the scene's bounds, anything else (a point light, a wider spot, the
// emitting triangles of one mesh) six cube faces around its position (the mesh's centroid for area
// lights). Views follow moving lights: rebuild them whenever the lights change.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "gl/frame/gpu_scene.h"

namespace bounce::gl {

struct LightView {
    glm::mat4 view{1.0f};
    glm::mat4 proj{1.0f};
    glm::vec3 origin{0.0f};    // light position (orthographic: the view's eye point)
    glm::vec3 direction{0.0f}; // view axis; for orthographic views the direction light travels
    bool orthographic = false;
    bool cubeFace = false;            // one of six 90-degree faces (cubeViews)
    float fovRad = 0.0f;              // perspective field of view of the square view
    float far = 0.0f;                 // perspective far plane; 0 for orthographic views
    float orthoHalfExtent = 0.0f;     // orthographic: half the side of the square the view covers (m)
    int light = -1;                   // index into GpuScene::lights() (area: the first triangle of its mesh)
    int areaFirst = 0, areaCount = 0; // area emitter: its triangles are lights [areaFirst, areaFirst + areaCount)
};

// What differs between the maps that share the builder.
struct LightViewOptions {
    // A spot whose outer cone (half-angle) is at most this gets one perspective view, a wider one a cube.
    float maxSingleViewConeRad = glm::radians(60.0f);
    // The single view's field of view: min(2 x outer cone x fovMargin, maxFovRad). The shadow maps keep
    // a 2% margin so that PCF taps at the cone's edge stay inside the map; the RSM covers exactly the
    // cone (Eq. 4's texel solid angle is the frustum's over size^2).
    float fovMargin = 1.0f;
    float maxFovRad = glm::radians(170.0f);
};

struct LightViews {
    std::vector<LightView> views;
    // Per light of GpuScene::lights(): (first view, view count); the area triangles of one mesh share
    // the cube of their mesh.
    std::vector<glm::ivec2> lightViews;
};

// Views of every light; none for a scene without geometry (empty bounds).
LightViews buildLightViews(const std::vector<LightSource>& lights, const core::Bounds& bounds,
                           const LightViewOptions& options = {});

// Near and far planes that keep the whole scene in view of a light at `origin`; the near plane stays
// small enough for a light 1 mm from a surface.
void lightNearFar(const core::Bounds& b, const glm::vec3& origin, float& near, float& far);
// An up vector for a light looking along d (any direction not parallel to it).
glm::vec3 lightUpVector(const glm::vec3& d);
// The six cube-face views around `origin`, in glsl/common/scene.glsl's cubeFace() order.
std::vector<LightView> cubeViews(const glm::vec3& origin, float near, float far);

} // namespace bounce::gl
