// The frame every technique shares (DESIGN.md, data flow): the scene on the GPU, shadow maps, the
// G-buffer, direct light, and the indirect-light texture a technique writes; composite = direct +
// indirect. Passes are timed through PassTimers under stable names ("shadow", "gbuffer", "direct"...).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include <glm/glm.hpp>

#include "core/image.h"
#include "core/scene.h"
#include "gl/frame/edge_antialias.h"
#include "gl/frame/frame_sampler.h"
#include "gl/frame/gpu_scene.h"
#include "gl/frame/ray_caster.h"
#include "gl/frame/scene_program.h"
#include "gl/frame/shadow_maps.h"
#include "gl/resource/buffer.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

class JointUpsample;

struct FrameSettings {
    int width = 512;
    int height = 512;
    int shadowMapSize = 1024;
    int shadowCascades = 3;         // a directional light's views fitted to the camera, beside its whole-scene view
    float shadowFootprint = 4.0f;   // a spot's or point light's texels per screen pixel (ShadowMaps; 0: shadowMapSize)
    int pcfRadius = 1;              // 0: one hard tap per pixel
    bool pcfLinear = true;          // hardware 2x2 bilinear comparison
    bool accumulate = true;         // still frames jitter the pixel centre and are averaged (gl/renderer.h)
    bool areaPcss = false;          // moving frames: area lights' penumbrae estimated by PCSS (else hard, centroid)
    bool stillRayShadows = true;    // still frames: shadow rays through the BVH (RAY_SHADOWS), not the shadow maps
    int stillDirectSamples = 1;     // still frames: the direct light's points per pixel (renderDirectSubsamples)
    int movingDirectSamples = 1;    // moving frames: the same (renderDirectSubsamples)
    bool temporal = false;          // temporal reuse of the technique's indirect light (gl/renderer.h)
    float temporalAlpha = 0.2f;     //   its weight of the new frame (TemporalReuseSettings::alpha)
    bool temporalClamp = true;      //   its neighbourhood clamp (TemporalReuseSettings::clamp)
    bool temporalDirect = false;    //   with it, the direct light's reuse in moving frames (gl/renderer.h)
    bool temporalCatmullRom = true; // its history resampled by Catmull-Rom (TemporalReuseSettings::catmullRom)
    bool edgeAntialias = false;     // moving frames: edges antialiased by their lines (gl/frame/edge_antialias.h)
    int textureSize = 512;          // base-colour textures are resampled to this size (normal maps keep theirs)
    bool normalMaps = true;         // the G-buffer's normals bent by the scene's normal maps (NORMAL_MAPS)
    // Profiling only (bench/sponza-gbuffer.json): the G-buffer pass with a fragment shader that writes
    // constants, to tell fragment work from vertex work and triangle setup. The images are wrong.
    bool gbufferConstantFragment = false;
};

// Counters that change when the scene, a light or the camera moves (and only then): progressive
// techniques compare them with what they accumulated for and start over.
struct FrameVersion {
    std::uint64_t scene = 0;  // geometry: moveVertices() (a Frame holds one scene)
    std::uint64_t lights = 0; // setLights()
    std::uint64_t camera = 0; // setCamera() with a different camera, resize()
    bool operator==(const FrameVersion&) const = default;
};

class Frame {
public:
    Frame(const core::Scene& scene, const FrameSettings& settings);
    ~Frame();

    void setCamera(const core::Camera& camera);
    void setLights(const std::vector<core::Light>& lights); // moves punctual lights, re-renders shadows
    // Deforming geometry (micro-rendering §2.1, point projection §4 "Scene Manipulation"): every vertex's new
    // position and normal (GpuScene::moveVertices), and version().scene changes. The rasterised passes
    // (G-buffer, shadow maps, RSMs), the area lights and emissive triangles, and the shared point clouds
    // follow: their points ride on their triangles' barycentrics and their areas scale with their triangles'
    // (PointCloud), and so does rayCaster(). What a technique builds on the CPU it builds from movedScene(), again
    // when version().scene changes. The path tracer is not the frame's and stays as it was.
    // False (nothing changed) for counts that differ from the scene's vertices or a value that is not finite.
    bool moveVertices(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals);
    // Whether the direct pass adds the light that emitting triangles reflect (on by default). Off for a
    // technique that carries the emitters' light itself and writes it into indirect() (grb's
    // emitters=bundles): the direct pass then holds emission and punctual lights only. The Renderer sets
    // it from Technique::carriesEmittersLight() before every frame. Off, the emitters' shadow cubes are not
    // rendered either unless keepAreaShadowMaps (Technique::readsAreaShadowMaps).
    void setAreaLightsInDirect(bool on, bool keepAreaShadowMaps = true);
    // Whether the technique reads the shadow maps (Technique::readsShadowMaps; the Renderer sets it before
    // every frame). False: renderShadowMaps() draws none in the frames whose direct pass reads none either
    // (the still form with shadow rays, shadow.still=rays: still frames, and moving frames with the reuse of
    // the direct light), and the frame's shadow counters read 0 there.
    void setShadowMapsRead(bool read) { shadowMapsRead_ = read; }
    bool areaLightsInDirect() const { return areaLightsInDirect_; }
    void resize(int width, int height);

    // The frame's own passes, in order: shadow maps, G-buffer, direct light. Then the technique runs,
    // then composite(). beginFrame advances the sampler (sampler()): `still` (gl/renderer.h decides when
    // the view is still) makes this frame the next still frame, which samples each pixel at its centre plus
    // the sampler's jitter (the G-buffer, so everything that reads it, and projection()) and moves the
    // frame's other stochastic parts (shadow-map shifts, area-light points) to their next sample; a moving
    // frame (still false) is still frame 0: pixel centres, the plain shadow maps.
    void beginFrame(bool still = false);
    void renderShadowMaps(PassTimers& timers);
    void renderGBuffer(PassTimers& timers);
    void renderDirect(PassTimers& timers);
    // Before renderGBuffer in a frame with N > 1 points of its direct light (still.directSamples in a still
    // frame, moving.directSamples in a moving one): the G-buffer and the direct light at the frame's N - 1
    // further points in the pixel (FrameSampler::setDirectSubsample), summed ("direct.samples"); the
    // renderDirect that follows at the frame's own point, whose G-buffer the technique reads (a moving
    // frame's: the pixel centres, where the reuse reprojects), leaves the mean of all N in direct(). The
    // emitters' points and shadow-map shifts stay one per frame, and so does the emitters' share of the
    // moving frames' ratio estimator (areaVisibility: the frame's own point's). Nothing at a coarser
    // indirect scale or with N = 1.
    void renderDirectSubsamples(PassTimers& timers);
    // direct + indirect into result(). withIndirect false (a technique that claims only direct light): no
    // pass at all, result() is the direct texture itself.
    void composite(PassTimers& timers, bool withIndirect = true);
    // Indirect light at 1/scale of the frame's resolution (the demo's frame budget while the view moves,
    // `render --indirect-scale`): from beginIndirect(scale) to endIndirect() the frame is ceil(w/scale) x
    // ceil(h/scale) to whatever a technique reads of it: width(), height(), bindGBuffer(), geometry(),
    // diffuse(), depth(), direct(), indirect(), projection(), readPositions()... are the coarse targets',
    // which beginIndirect renders from the same camera (the G-buffer; the direct light when `withDirect`,
    // for a technique that reads it) and whose indirect light it clears. Shadow maps, lights, the GPU
    // scene and the ray caster are the frame's own at every scale, so a technique keeps what it built
    // (one instance at every scale, gl/renderer.h). endIndirect brings the coarse indirect light into the
    // full frame's indirect() by joint bilateral upsampling (gl/frame/joint_upsample.h), which writes every
    // pixel of it: the full frame's indirect light is cleared only at scale 1, where beginIndirect clears it
    // and endIndirect does nothing. Throws std::invalid_argument outside 1..16.
    void beginIndirect(int scale, PassTimers& timers, bool withDirect);
    void endIndirect(PassTimers& timers);
    // The scale of the targets now in use: beginIndirect's inside the pair, 1 outside it.
    int indirectScale() const { return coarseActive_ ? scale_ : 1; }
    // The frame index, the still index and the pixel jitter, and every sample stream the frame and the
    // techniques draw from (gl/frame/frame_sampler.h).
    const FrameSampler& sampler() const { return sampler_; }
    // After composite(), for still frame 1 and later: result() becomes the mean of the still frames'
    // results ("accumulate" pass), so that a still view converges to box-filtered pixels. A progressive
    // technique (its indirect light is already its own running mean, but taken at each frame's sample
    // position in the pixel) gets the mean of the direct light plus the mean of its indirect light with
    // frame n weighing n^3, so that its early frames fade. Still frame 0: nothing, result() is this frame's.
    void accumulate(PassTimers& timers, bool progressive);
    // After composite(), before accumulate(): in a frame that is not a still frame (still index 0), with the
    // frame parameter edgeAA, result() becomes the composited light with its geometric edges antialiased
    // (gl/frame/edge_antialias.h). Still frames average jittered pixels instead; their result() is left as
    // it is.
    void antialiasEdges(PassTimers& timers);
    void clearIndirect();

    // Binds the G-buffer (glsl/common/gbuffer.glsl): its textures at UNIT_G_*, a 1x1 black texture for a
    // target the scene does not need, and the camera block at UBO_GBUFFER_CAMERA.
    void bindGBuffer() const;
    // SCENE_DIFFUSE_ONLY / SCENE_NO_EMITTERS / SCENE_NO_TEXTURES where the scene has no glossy material /
    // no emitter / no base-colour texture: a program compiled with them reads no texel for what is not
    // there (common/gbuffer.glsl, brdf.glsl, base_color.glsl). Programs without them read the black 1x1
    // texture instead, and are right too.
    std::vector<Define> gbufferDefines() const;
    // The frame's direct-light estimator (glsl/common/lighting.glsl, addDirectLight), which every pass that
    // lights a point with the scene's lights runs, so that a pixel and a ray hit at one point get the same
    // light: directLightDefines(still) are its defines for the kinds of light the scene has, in the still
    // frames' form (emitters sampled at this frame's point, cascades) or the moving frame's (PCSS when asked
    // for); directLightStill() says which form this frame runs (the still one from still frame 1 on, where
    // it differs); setDirectLightUniforms sets the lights' counts, the shadow maps' filter and the still
    // frame's rotation of the emitters' glossy points. A program built on them compiles once per form it
    // meets.
    bool directLightStill() const;
    std::vector<Define> directLightDefines(bool still) const;
    // The still frames' shadow rays' defines (RAY_SHADOWS, and ALPHA_MASK where the scene has masks) where the
    // frame casts them (shadow.still=rays, a scene with lights), else none; the bound scene data
    // (bindSceneData) carries the BVH they walk.
    std::vector<Define> shadowRayDefines() const;
    void setDirectLightUniforms(Program& program) const;
    bool hasSpecularTarget() const { return bool(full_.specular); }
    bool hasEmissionTarget() const { return bool(full_.emission); }
    // Binds materials (SSBO 0), lights (1), shadow views (2), area polygons (3), the scene's geometry
    // (vertices 4, indices 5, emissive triangles 6: glsl/common/scene.glsl with SCENE_GEOMETRY), shadow
    // depth (unit 5) and the base-colour textures (unit 6); with shadow.still=rays the BVH of rayCaster() too
    // (SSBO 18, 19), which the still frames' estimator walks.
    void bindSceneData() const;
    void drawFullscreen() const;

    const core::Scene& scene() const { return scene_; } // as loaded
    // The scene with the vertices as moveVertices() last left them (scene() until then).
    const core::Scene& movedScene() const { return moved_ ? *moved_ : scene_; }
    const GpuScene& gpuScene() const { return gpu_; }
    // Ray casting for every family (glsl/common/raycast.glsl): the BVH of movedScene(), built at the first call
    // and again at the first call after moveVertices() changed version().scene, so that rays meet the geometry
    // the rasterised passes draw. No family builds a BVH of its own: each asks for it in every frame it casts
    // rays in (the call rebuilds what moved). Rebuilt in place, the object lives as long as the frame.
    const RayCaster& rayCaster() const;
    const ShadowMaps& shadowMaps() const { return shadows_; }
    // The lights as the shaders read them (gl/frame/frame_lights.h), bound by bindSceneData().
    const FrameLights& lights() const { return lights_; }
    const FrameSettings& settings() const { return settings_; }
    // Moving frames' points of the direct light from the next frame on (FrameSettings::movingDirectSamples,
    // at least 1): the demo's frame budget sets it without rebuilding the frame (app/demo_script.h).
    void setMovingDirectSamples(int n) { settings_.movingDirectSamples = n > 1 ? n : 1; }
    const core::Camera& camera() const { return camera_; }
    glm::mat4 view() const { return camera_.view(); }
    // The camera's projection, offset by the still frame's sub-pixel jitter (sampler().jitter()).
    glm::mat4 projection() const;
    // The targets in use (beginIndirect): the frame's size, or the coarse size inside beginIndirect.
    int width() const { return targets().width; }
    int height() const { return targets().height; }
    const FrameVersion& version() const { return version_; }

    // RG32UI: eye depth bits (0: background) and the octahedral normal (glsl/common/gbuffer.glsl).
    const Texture& geometry() const { return targets().geometry; }
    const Texture& diffuse() const { return targets().diffuse; }
    const Texture& depth() const { return targets().depth; }
    const Texture& direct() const { return targets().direct; }
    Texture& direct() { return targets().direct; } // temporal reuse writes it (gl/renderer.h)
    Texture& indirect() { return targets().indirect; }
    // Moving frames with the reuse of their direct light in a scene with emitting triangles
    // (`temporal.direct`; common/lighting.glsl, areaLightsRatio): the direct pass wrote the emitters' light
    // apart, as its exact unshadowed value and this frame's sums of w V and w (areaVisibility(), RGBA32F:
    // r and g), and direct() holds the rest. The Renderer averages areaVisibility() over the frames
    // (TemporalReuse), then resolveAreaRatio() adds the unshadowed light times the mean of w V over the mean
    // of w to direct(). areaRatioDrawn(): whether the last full-size direct pass took this form (false
    // otherwise, and resolveAreaRatio() does nothing).
    bool areaRatioDrawn() const { return areaRatioDrawn_; }
    Texture& areaVisibility() { return areaRatio_.visibility; }
    void resolveAreaRatio(PassTimers& timers);
    const Texture& result() const
    {
        return accumulatedResult_ ? accumulated_
               : edgeAAUsed_      ? edgeAA_->result()
               : compositeUsed_   ? composite_
                                  : full_.direct;
    }

    // Reads an RGBA32F texture back as an RGB image, row 0 at the top.
    core::Image read(const Texture& texture) const;
    // The G-buffer as the shaders' accessors see it, decoded on the GPU into RGBA32F, GL rows (row 0 at
    // the bottom), four floats per pixel: world position and 1 where there is geometry (0 elsewhere),
    // and the unit normal and eye depth. For tests and tools.
    std::vector<float> readPositions() const;
    std::vector<float> readNormals() const;
    // Emitted radiance as seen by the camera (black without an emission target), row 0 at the top.
    core::Image readEmission() const;
    // Four floats per pixel in GL rows (readFloats, readPositions) as an RGB image, row 0 at the top.
    core::Image toImage(const std::vector<float>& rgba) const;

private:
    const core::Scene& scene_;
    std::unique_ptr<core::Scene> moved_; // movedScene() once moveVertices() moved something
    FrameSettings settings_;
    core::Camera camera_;
    GpuScene gpu_;
    FrameLights lights_; // written by shadows_
    ShadowMaps shadows_;
    mutable std::unique_ptr<RayCaster> rayCaster_; // rayCaster(), built on first use
    mutable std::uint64_t rayCasterScene_ = 0;     // the version().scene it was built for
    // What the frame renders per pixel, at its own size (full_) and at beginIndirect's (coarse_).
    struct Targets {
        int width = 0, height = 0;
        Texture geometry, diffuse, specular, emission, depth, direct, indirect;
        Buffer camera; // glsl/common/gbuffer.glsl's GBufferCamera for this size
        Framebuffer gbufferFbo, directFbo;
    };
    Targets full_, coarse_;
    bool coarseActive_ = false; // inside beginIndirect(scale > 1)
    int scale_ = 1;
    std::unique_ptr<JointUpsample> upsample_;
    std::unique_ptr<EdgeAntialias> edgeAA_; // made by the first frame that antialiases its edges
    bool edgeAAUsed_ = false;               // result() is edgeAA_'s
    Targets& targets() { return coarseActive_ ? coarse_ : full_; }
    const Targets& targets() const { return coarseActive_ ? coarse_ : full_; }
    Texture composite_;
    Texture black_;               // 1x1, bound for the targets the scene does not need
    Texture accumulated_;         // still frames' mean (accumulate()), allocated at the first still frame
    Texture accumulatedIndirect_; // a progressive technique's indirect light, weighted over the still frames
    Framebuffer compositeFbo_;
    VertexArray emptyVao_;
    SceneProgram gbufferProgram_;
    Program directProgram_, directStillProgram_, compositeProgram_, accumulateProgram_, accumulateDirectProgram_;
    Program directRatioProgram_; // moving frames with temporal.direct and emitters (areaRatioDrawn())
    struct AreaRatio {
        Texture unshadowed, visibility; // full size, allocated at the first frame that draws them
        Framebuffer fbo{"direct.ratio.fbo"};
        unsigned direct = 0; // the id of full_.direct that fbo draws into (a reallocated target remakes it)
        Program resolve;
    };
    AreaRatio areaRatio_;
    Texture directSum_; // renderDirectSubsamples' sum, allocated at its first use
    Program directSumProgram_, directMeanProgram_;
    int directSubsamplesPending_ = 0; // N where renderDirect is to leave the mean of N points, else 0
    void runDirectSamples(PassTimers& timers, bool resolve, bool first);
    void drawDirect(PassTimers& timers); // renderDirect's pass, without the mean of renderDirectSubsamples
    bool areaRatioDrawn_ = false;
    void allocateAreaRatio();
    // Whether this frame's own direct pass runs its still form (renderDirect; the shadow pass asks too).
    bool directPassStill() const { return sampler_.sampleIndex() > 0 && directStillProgram_; }
    bool compositeUsed_ = true;
    bool areaLightsInDirect_ = true;
    bool shadowMapsRead_ = true;     // setShadowMapsRead
    bool accumulatedResult_ = false; // result() is accumulated_
    FrameSampler sampler_;
    FrameVersion version_;
    void allocateTargets();
    void allocate(Targets& t, int width, int height, const std::string& suffix);
    void rebuildDirectPrograms();
    // Runs `change` on the GPU scene's lights or geometry, then fits the shadow maps' views to what it left,
    // and rebuilds the direct pass's programs where a kind of light (punctual, directional, area) came or went.
    void changeLights(const std::function<void()>& change);
    void updateGBufferCamera();
    std::vector<float> decode(int output) const;
};

} // namespace bounce::gl
