// The views a light is seen from: the one type of light view for every map rendered from the lights
// (shadow maps, reflective shadow maps, an area light's still-frame shadow cubes): a spot with a narrow enough cone gets one perspective view, a directional light one
// orthographic view fitted to the scene's bounds, anything else (a point light, a wider spot, the
// emitting triangles of one mesh) six cube faces around its position (the mesh's centroid for area
// lights). Views follow moving lights: rebuild them whenever the lights change.
#pragma once

#include <cmath>
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
    bool cascade = false;             // orthographic view fitted to a slice of the camera's frustum
    float fovRad = 0.0f;              // perspective field of view of the square view
    float far = 0.0f;                 // perspective far plane; 0 for orthographic views
    float orthoHalfExtent = 0.0f;     // orthographic: half the side of the square the view covers (m)
    int light = -1;                   // index into GpuScene::lights() (area: the first triangle of its mesh)
    int areaFirst = 0, areaCount = 0; // area emitter: its triangles are lights [areaFirst, areaFirst + areaCount)

    // The side of one of size x size texels at the view's centre: at distance 1 for a perspective view
    // (a cube face's 90 degrees included), in metres for an orthographic one (the larger side of a
    // cascade's rectangle).
    float texelSide(int size) const
    {
        return orthographic ? 2.0f * orthoHalfExtent / float(size) : 2.0f * std::tan(0.5f * fovRad) / float(size);
    }
};

// The camera a directional light's shadow views are fitted to (cascaded shadow maps): where it looks from,
// its field of view and aspect, and how many cascades. Without one (cascades 0), a directional light gets
// the one view over the whole scene.
struct ViewFit {
    core::Camera camera;
    float aspect = 1.0f;
    int cascades = 0;
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
    // Shadow maps: a directional light's cascades (ViewFit); the RSM keeps the whole scene in one view.
    ViewFit fit;
};

struct LightViews {
    std::vector<LightView> views;
    // Per light of GpuScene::lights(): (first view, view count); the area triangles of one mesh share
    // the cube of their mesh.
    std::vector<glm::ivec2> lightViews;
};

// Views of every light; none for a scene without geometry (empty bounds). A directional light with
// options.fit.cascades > 0 gets that many orthographic views fitted, in light space, to consecutive depth
// slices of the camera's frustum within the scene's bounds (near to far, each over every caster along the
// light), then the view over the whole scene for what no cascade covers (points off screen).
LightViews buildLightViews(const std::vector<LightSource>& lights, const core::Bounds& bounds,
                           const LightViewOptions& options = {});

// Near and far planes that keep the whole scene in view of a light at `origin`; the near plane stays
// small enough for a light 1 mm from a surface.
void lightNearFar(const core::Bounds& b, const glm::vec3& origin, float& near, float& far);
// The distances along the camera's view axis between which its frustum meets the box b ({0, 0} when it
// misses it), and the light-space rectangle (xy of `lightView` applied) that frustum slice [d0, d1] within b
// covers, as lo.xy, hi.xy; false when the slice misses the box.
glm::vec2 viewDepthRange(const ViewFit& fit, const core::Bounds& b);
bool sliceLightRect(const ViewFit& fit, float d0, float d1, const core::Bounds& b, const glm::mat4& lightView,
                    glm::vec4& rect);
// The practical split scheme (Zhang et al. 2006): distance i of n slices over [near, far], the mean of the
// logarithmic and the uniform split.
float cascadeSplit(float near, float far, int i, int n);
// The side, in texels, at which a perspective light view's map has one texel per screen pixel over what
// the camera sees of it (a spot or point light's shadow map sized from its screen footprint, issue 26):
// the region the view, the camera's frustum (width/height pixels, fit.aspect = width / height) and the
// box b have in common, whose bounding rectangle spans S_x x S_y pixels on screen and the fraction
// L_x x L_y of the view's [-1, 1]^2; the side is sqrt(S_x S_y / (L_x L_y)), the texel density of the
// screen averaged over the region. 0 when the camera sees nothing the view covers.
float footprintSide(const LightView& view, const ViewFit& fit, int height, const core::Bounds& b);
// An up vector for a light looking along d (any direction not parallel to it).
glm::vec3 lightUpVector(const glm::vec3& d);
// The six cube-face views around `origin`, in glsl/common/scene.glsl's cubeFace() order.
std::vector<LightView> cubeViews(const glm::vec3& origin, float near, float far);

} // namespace bounce::gl
