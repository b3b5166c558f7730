// Shadow maps of every light in one depth array texture, one layer per view of gl/frame/light_views.h:
// a spot gets one perspective layer (a cube when its cone is wider than 120 degrees), a point light six cube-face layers, the area lights of one
// emitting mesh one shared cube at its centroid, a directional light one orthographic layer fitted to
// the scene. Writes the frame's light records (FrameLights: each light's shadow layers and views, an
// emitter's point in still frames, the area lights' triangles). Only what the lights need is allocated.
//
// A spot's or point light's view is rendered at a side chosen from its footprint on screen (footprint > 0,
// fitTo): `footprint` texels per pixel of what the camera sees of it (footprintSide), rounded up to a power
// of two and clamped to [min(kMinFootprintSide, size), size], into the corner of its layer; the view's
// lookup matrix maps into that corner and glsl/common/shadow.glsl keeps the taps inside it. A light far
// away or off screen then costs a small map, one the camera sees close up the full size; the area lights'
// cubes (moved in still frames) and the sun's views (cascades fit the camera already) stay whole.
//
// Still frames (the frame sampler's still index >= 1) sample what one map cannot hold, so that their mean converges:
//   - every view is shifted by a sub-texel Halton offset (the taps' positions on the surfaces change), so
//     that one nearest tap per frame averages to the exact hard shadow of a point light, spot or the sun;
//   - an area emitter's cube moves to a point sampled uniformly over the emitting mesh's area (scrambled
//     Sobol points, FrameSampler's AreaLightPoint, stratified over the frames) and the triangle that holds it
//     carries the mesh's area (GpuLight::sampleArea, 0 on the others): glsl/frame/direct.frag's sum of
//     areaSampleUnshadowed is then the
//     one-sample estimate L A cos cos / r^2 V of the emitter's direct light, whose mean over the frames is
//     the path tracer's soft shadow. Frame 0 (and a moving view): the cube at the centroid, unshifted.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "gl/frame/frame_lights.h"
#include "gl/frame/gpu_scene.h"
#include "gl/frame/light_views.h"
#include "gl/frame/scene_program.h"
#include "gl/resource/buffer.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/handle.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"

namespace bounce::gl {

struct SamplerDeleter {
    void operator()(unsigned id) const;
};

class ShadowMaps {
public:
    // The smallest side a footprint chooses: points off screen (the lit point clouds, the ray-bundle atlases)
    // read the same maps.
    static constexpr int kMinFootprintSide = 256;
    // size: the layers' side, the largest a view gets; cascades: a directional light's views fitted to the
    // camera (fitTo), beside its whole-scene view; footprint: texels per screen pixel of a spot's or point
    // light's views (0: every view at `size`).
    // lights: the frame's records, which the shadow maps write (it must outlive them).
    ShadowMaps(const GpuScene& scene, FrameLights& lights, int size, int cascades = 0, float footprint = 0.0f);
    // Fits a directional light's cascades and the spots' and point lights' sides to the camera, a width x
    // height image (nothing to do without such lights, or when it has not moved).
    void fitTo(const core::Camera& camera, int width, int height);
    // Recomputes views and light buffers after lights moved (keeps the texture when the layer count holds).
    void update(const GpuScene& scene);
    void render(const GpuScene& scene);
    // Whether render() draws the emitting meshes' cubes (on by default). Off while nothing reads them: a
    // technique that carries the emitters' light itself and samples none (Frame::setAreaLightsInDirect).
    void setAreaViews(bool on) { areaViews_ = on; }
    // Whether render() draws anything this frame (on by default). Off while nothing reads the maps
    // (Frame::setShadowMapsRead): the maps then hold whatever an earlier frame drew.
    void setRendered(bool on) { rendered_ = on; }
    // Whether render() draws view i this frame: a cascade in still frames only, an emitter's cube unless
    // setAreaViews(false).
    bool renders(std::size_t i) const
    {
        return rendered_ && !(views_[i].cascade && still_ == 0) && (areaViews_ || views_[i].areaCount == 0);
    }
    // The views each ShadowMaps' views() that render() draws this frame.
    int renderedViewCount() const;
    // The views and lights of still frame `index` (see above); 0 restores the plain ones.
    void setStill(int index);
    bool hasAreaLights() const { return !areaGroups_.empty(); }
    // The depth array at UNIT_SHADOW_MAPS (and at UNIT_SHADOW_DEPTHS without comparison, for
    // glsl/common/shadow.glsl's SHADOW_PCSS); the views are the frame's lights' (FrameLights).
    void bind() const;
    void setPcf(bool hardwareFilter);
    // The PCF uniforms of glsl/common/shadow.glsl on a program that includes it: the kernel radius, and
    // whether the taps are nearest (the shader gathers texels itself and weights them as the filter would).
    // Still frames: one nearest tap, whatever the radius (see above).
    void setPcfUniforms(Program& program, int radius) const;

    // This frame's views (still frames: shifted, the area lights' cubes moved; a cascade is rendered in
    // still frames only).
    const std::vector<LightView>& views() const { return views_; }
    const Texture& depth() const { return depth_; }
    int size() const { return size_; }
    // Per view of views(): the side it is rendered at (size() unless its footprint chose less).
    const std::vector<int>& sides() const { return sides_; }
    // The texels render() draws this frame (the views it renders, each side^2).
    double renderedTexels() const;

private:
    int size_;
    float footprint_;
    FrameLights* lights_; // the frame's records, which upload() writes
    std::vector<LightView> views_;
    std::vector<int> sides_;
    LightViews lightViews_;              // the plain views (setStill shifts and moves copies of them)
    std::vector<LightSource> sources_;   // the lights they were built for
    std::vector<glm::ivec2> areaGroups_; // per emitting mesh: first light, triangle count
    core::Bounds bounds_;
    int still_ = 0;
    bool areaViews_ = true;
    bool rendered_ = true;
    ViewFit fit_;
    bool fitted_ = false; // fit_.camera has been set
    int height_ = 0;      // the image fit_ is for, in pixels
    Texture depth_;
    mutable Handle<SamplerDeleter> rawSampler_; // nearest, no comparison: the depths PCSS averages
    Framebuffer fbo_;
    SceneProgram program_;
    std::vector<glm::vec4> polygons_; // the area lights' triangles, for FrameLights
    bool linear_ = true;
    void buildViews(const GpuScene& scene);
    void upload(); // views_ and the light records for still_, into FrameLights
    std::vector<int> footprintSides() const;
};

} // namespace bounce::gl
