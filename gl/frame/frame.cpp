#include "gl/frame/frame.h"

#include <algorithm>
#include <stdexcept>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "core/sampling.h"
#include "gl/frame/bindings.h"
#include "gl/frame/frame_budget.h"
#include "gl/frame/joint_upsample.h"
#include "gl/frame/shader_costs.h"
#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/resource/pass_state.h"

namespace bounce::gl {

namespace {

// What the scene lacks, for the programs specialised to it: no glossy lobe (no specular target, no GGX
// terms), no emitter (no emission target), no base-colour texture (no lookup): common/gbuffer.glsl,
// common/brdf.glsl, common/base_color.glsl.
std::vector<Define> sceneDefines(const core::Scene& scene, const GpuScene& gpu)
{
    std::vector<Define> d;
    if (!scene.hasGlossy()) d.push_back({"SCENE_DIFFUSE_ONLY", "1"});
    if (gpu.emissiveTriangleCount() == 0) d.push_back({"SCENE_NO_EMITTERS", "1"});
    if (!gpu.hasTextures()) d.push_back({"SCENE_NO_TEXTURES", "1"});
    return d;
}

// The directional lights' cascades the still frames render and read: none where they cast shadow rays,
// whose estimator reads no map (the moving frames and every other pass read the whole-scene view).
int stillCascades(const FrameSettings& settings)
{
    return settings.stillRayShadows ? 0 : settings.shadowCascades;
}

// Whether the direct pass lights emitting triangles: the scene has some and the technique leaves them to it
// (areaLights, Frame::setAreaLightsInDirect).
bool areaLightsLit(const GpuScene& gpu, bool areaLights)
{
    return areaLights && int(gpu.lights().size()) > gpu.punctualLightCount();
}

// Shadow rays (common/shadow.glsl, RAY_SHADOWS) where the frame casts them (shadow.still=rays, a scene with
// lights): the BVH's walk, which skips the masks' holes (ALPHA_MASK).
std::vector<Define> shadowRayDefines(const GpuScene& gpu, const FrameSettings& settings)
{
    if (!settings.stillRayShadows || gpu.lights().empty()) return {};
    std::vector<Define> d{{"RAY_SHADOWS", "1"}};
    if (gpu.hasAlphaMask()) d.push_back({"ALPHA_MASK", "1"});
    return d;
}

// The defines of the frame's direct-light estimator (glsl/common/lighting.glsl, addDirectLight) for the kinds
// of light the scene has: a loop over a kind the scene lacks still costs a masked pass through its body on a
// SIMD rasteriser (llvmpipe), the polygon form factor of the emitting triangles most of all.
// still: the still frames' form, where it differs from the moving frame's: area lights sampled on the
// emitter (AREA_SAMPLED), a directional light's cascades read (SHADOW_CASCADES). Moving: the area lights'
// PCSS when asked for. areaLights false: no emitting triangle (Frame::setAreaLightsInDirect).
std::vector<Define> directLightKinds(const GpuScene& gpu, const FrameSettings& settings, bool still, bool areaLights)
{
    std::vector<Define> kinds;
    const bool area = areaLightsLit(gpu, areaLights);
    const bool cascades = stillCascades(settings) > 0 && hasLightOfType(gpu.lights(), kLightDirectional);
    if (gpu.punctualLightCount() > 0) kinds.push_back({"PUNCTUAL_LIGHTS", "1"});
    if (area) kinds.push_back({"AREA_LIGHTS", "1"});
    if (still && area) kinds.push_back({"AREA_SAMPLED", "1"});
    if (still && cascades) kinds.push_back({"SHADOW_CASCADES", "1"});
    if (!still && area && settings.areaPcss) kinds.push_back({"SHADOW_PCSS", "1"});
    if (still) {
        const std::vector<Define> rays = shadowRayDefines(gpu, settings);
        kinds.insert(kinds.end(), rays.begin(), rays.end());
    }
    return kinds;
}

// Whether the still frames' estimator differs from the moving frame's (directLightKinds).
bool stillFormDiffers(const GpuScene& gpu, const FrameSettings& settings, bool areaLights)
{
    const bool area = areaLightsLit(gpu, areaLights);
    return area || (stillCascades(settings) > 0 && hasLightOfType(gpu.lights(), kLightDirectional)) ||
           (settings.stillRayShadows && !gpu.lights().empty());
}

// The direct-light program: emission plus the estimator at every pixel. The still program is none where
// the still form is the moving one.
Program directProgram(const core::Scene& scene, const GpuScene& gpu, const FrameSettings& settings, bool still = false,
                      bool areaLights = true)
{
    if (still && !stillFormDiffers(gpu, settings, areaLights)) return Program();
    std::vector<Define> kinds = sceneDefines(scene, gpu);
    const std::vector<Define> light = directLightKinds(gpu, settings, still, areaLights);
    kinds.insert(kinds.end(), light.begin(), light.end());
    return Program::graphics(still ? "direct.still" : "direct", "frame/fullscreen.vert", "frame/direct.frag", kinds);
}

// Whether moving frames write the area lights' ratio estimator (common/lighting.glsl, areaLightsRatio): the
// reuse of their direct light is on (`temporal`, `temporal.direct`) and the direct pass lights the scene's
// emitting triangles.
bool usesAreaRatio(const GpuScene& gpu, const FrameSettings& settings, bool areaLights)
{
    return settings.temporal && settings.temporalDirect && areaLightsLit(gpu, areaLights);
}

// The moving frames' direct program with the ratio estimator: the still form's samples (this frame's point
// on each emitter and its shadow ray or shifted cube), the emitters written apart (AREA_RATIO). None where
// usesAreaRatio is false.
Program directRatioProgram(const core::Scene& scene, const GpuScene& gpu, const FrameSettings& settings,
                           bool areaLights)
{
    if (!usesAreaRatio(gpu, settings, areaLights)) return Program();
    std::vector<Define> kinds = sceneDefines(scene, gpu);
    const std::vector<Define> light = directLightKinds(gpu, settings, true, areaLights);
    kinds.insert(kinds.end(), light.begin(), light.end());
    kinds.push_back({"AREA_RATIO", "1"});
    return Program::graphics("direct.ratio", "frame/fullscreen.vert", "frame/direct.frag", kinds);
}

SceneProgram gbufferProgram(const core::Scene& scene, const GpuScene& gpu, const FrameSettings& settings)
{
    std::vector<Define> defines = sceneDefines(scene, gpu);
    if (settings.gbufferConstantFragment) defines.push_back({"GBUFFER_CONSTANT_FRAGMENT", "1"});
    if (settings.normalMaps && gpu.hasNormalMaps()) defines.push_back({"NORMAL_MAPS", "1"});
    SceneProgram p("gbuffer", "frame/gbuffer.vert", "frame/gbuffer.frag", defines);
    p.prepare(gpu);
    return p;
}

// The block of glsl/common/gbuffer.glsl's GBufferCamera (std140: five vec4s).
struct GBufferCamera {
    glm::vec4 origin, corner, axisX, axisY;
    glm::ivec4 present;
};

} // namespace

Frame::Frame(const core::Scene& scene, const FrameSettings& settings)
    : scene_(scene),
      settings_(settings),
      camera_(scene.camera),
      gpu_(scene, settings.textureSize),
      shadows_(gpu_, lights_, settings.shadowMapSize, stillCascades(settings), settings.shadowFootprint),
      compositeFbo_("composite.fbo"),
      emptyVao_("fullscreen"),
      gbufferProgram_(gbufferProgram(scene, gpu_, settings)),
      directProgram_(directProgram(scene, gpu_, settings)),
      directStillProgram_(directProgram(scene, gpu_, settings, true)),
      compositeProgram_(Program::graphics("composite", "frame/fullscreen.vert", "frame/composite.frag")),
      accumulateProgram_(Program::compute("accumulate", "frame/accumulate.comp")),
      accumulateDirectProgram_(Program::compute("accumulate.direct", "frame/accumulate.comp", {{"ADD_INDIRECT", "1"}})),
      directRatioProgram_(directRatioProgram(scene, gpu_, settings, true))
{
    shadows_.setPcf(settings.pcfLinear);
    sampler_.setFreshMovingSeeds(settings.temporal);
    sampler_.setMovingSamples(settings.temporal && settings.temporalDirect);
    allocateTargets();
}

Frame::~Frame() = default;

void Frame::allocateTargets()
{
    // Before any target: a size the driver cannot hold stops the run at once.
    checkFrameFits(settings_, frameTargetBytesPerPixel(scene_.hasGlossy(), gpu_.emissiveTriangleCount() > 0));
    allocate(full_, settings_.width, settings_.height, "");
    coarse_ = Targets(); // allocated again by the next beginIndirect at the new size
    coarseActive_ = false;
    composite_ = Texture::create2D("composite", GL_RGBA32F, settings_.width, settings_.height);
    if (!black_) {
        black_ = Texture::create2D("frame.absentTarget", GL_RGBA16F, 1, 1);
        const float zero[4] = {0, 0, 0, 0};
        black_.clear(0, zero);
    }
    compositeFbo_.attach(GL_COLOR_ATTACHMENT0, composite_);
    compositeFbo_.checkComplete();
    accumulated_ = Texture();
    accumulatedIndirect_ = Texture();
    accumulatedResult_ = false;
    clearIndirect();
}

void Frame::allocate(Targets& t, int w, int h, const std::string& suffix)
{
    const bool glossy = scene_.hasGlossy(), emitters = gpu_.emissiveTriangleCount() > 0;
    t.width = w;
    t.height = h;
    t.geometry = Texture::create2D("gbuffer.geometry" + suffix, GL_RG32UI, w, h);
    t.diffuse = Texture::create2D("gbuffer.diffuse" + suffix, GL_RGBA16F, w, h);
    t.specular = glossy ? Texture::create2D("gbuffer.specular" + suffix, GL_RGBA16F, w, h) : Texture();
    t.emission = emitters ? Texture::create2D("gbuffer.emission" + suffix, GL_RGBA16F, w, h) : Texture();
    t.depth = Texture::create2D("gbuffer.depth" + suffix, GL_DEPTH_COMPONENT32F, w, h);
    t.direct = Texture::create2D("direct" + suffix, GL_RGBA32F, w, h);
    t.indirect = Texture::create2D("indirect" + suffix, GL_RGBA32F, w, h);
    t.gbufferFbo = Framebuffer("gbuffer.fbo" + suffix); // fresh objects: no attachment of an earlier size survives
    t.gbufferFbo.attach(GL_COLOR_ATTACHMENT0, t.geometry);
    t.gbufferFbo.attach(GL_COLOR_ATTACHMENT1, t.diffuse);
    if (t.specular) t.gbufferFbo.attach(GL_COLOR_ATTACHMENT2, t.specular);
    if (t.emission) t.gbufferFbo.attach(GL_COLOR_ATTACHMENT3, t.emission);
    t.gbufferFbo.attach(GL_DEPTH_ATTACHMENT, t.depth);
    t.gbufferFbo.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                                 GLenum(t.specular ? GL_COLOR_ATTACHMENT2 : GL_NONE),
                                 GLenum(t.emission ? GL_COLOR_ATTACHMENT3 : GL_NONE)});
    t.gbufferFbo.checkComplete();
    t.directFbo = Framebuffer("direct.fbo" + suffix);
    t.directFbo.attach(GL_COLOR_ATTACHMENT0, t.direct);
    t.directFbo.checkComplete();
    if (!t.camera) t.camera = Buffer("frame.gbufferCamera" + suffix, sizeof(GBufferCamera));
}

void Frame::beginIndirect(int scale, PassTimers& timers, bool withDirect)
{
    if (scale < 1 || scale > 16) throw std::invalid_argument("indirect scale must be in 1..16");
    scale_ = scale;
    if (scale == 1) {
        clearIndirect();
        return;
    }
    const int w = (settings_.width + scale - 1) / scale, h = (settings_.height + scale - 1) / scale;
    if (coarse_.width != w || coarse_.height != h) allocate(coarse_, w, h, ".coarse");
    coarseActive_ = true;
    renderGBuffer(timers); // the coarse targets' own, from the same camera
    if (withDirect) renderDirect(timers);
    clearIndirect();
}

void Frame::endIndirect(PassTimers& timers)
{
    if (!coarseActive_) return;
    coarseActive_ = false;
    if (!upsample_) upsample_ = std::make_unique<JointUpsample>();
    upsample_->run(*this, coarse_.geometry, coarse_.indirect, full_.geometry, full_.indirect, timers);
}

void Frame::setCamera(const core::Camera& camera)
{
    const auto same = [](const core::Camera& a, const core::Camera& b) {
        return a.position == b.position && a.forward == b.forward && a.up == b.up && a.yfovRad == b.yfovRad &&
               a.znear == b.znear && a.zfar == b.zfar;
    };
    if (same(camera, camera_)) return;
    camera_ = camera;
    ++version_.camera;
}

void Frame::setLights(const std::vector<core::Light>& lights)
{
    changeLights([&] { gpu_.setLights(lights); });
    ++version_.lights;
}

bool Frame::moveVertices(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals)
{
    bool moved = false;
    changeLights([&] { moved = gpu_.moveVertices(positions, normals); });
    if (!moved) return false;
    // Copied once (textures and all); later moves only write the vertices.
    if (!moved_) moved_ = std::make_unique<core::Scene>(scene_);
    moved_->setVertices(positions, normals);
    ++version_.scene;
    return true;
}

const RayCaster& Frame::rayCaster() const
{
    if (!rayCaster_)
        rayCaster_ = std::make_unique<RayCaster>(movedScene());
    else if (rayCasterScene_ != version_.scene)
        *rayCaster_ = RayCaster(movedScene());
    rayCasterScene_ = version_.scene;
    return *rayCaster_;
}

void Frame::changeLights(const std::function<void()>& change)
{
    const auto kinds = [&] {
        const int punctual = gpu_.punctualLightCount();
        return std::tuple(punctual > 0, hasLightOfType(gpu_.lights(), kLightDirectional),
                          int(gpu_.lights().size()) > punctual);
    };
    const auto before = kinds();
    change();
    shadows_.update(gpu_);
    if (kinds() != before) rebuildDirectPrograms();
}

void Frame::setAreaLightsInDirect(bool on, bool keepAreaShadowMaps)
{
    shadows_.setAreaViews(on || keepAreaShadowMaps);
    if (on == areaLightsInDirect_) return;
    areaLightsInDirect_ = on;
    rebuildDirectPrograms();
}

void Frame::rebuildDirectPrograms()
{
    directProgram_ = directProgram(scene_, gpu_, settings_, false, areaLightsInDirect_);
    directStillProgram_ = directProgram(scene_, gpu_, settings_, true, areaLightsInDirect_);
    directRatioProgram_ = directRatioProgram(scene_, gpu_, settings_, areaLightsInDirect_);
}

void Frame::resize(int width, int height)
{
    if (width == settings_.width && height == settings_.height) return;
    settings_.width = width;
    settings_.height = height;
    allocateTargets();
    ++version_.camera;
}

void Frame::beginFrame(bool still)
{
    sampler_.advance(still);
    accumulatedResult_ = false;
}

glm::mat4 Frame::projection() const
{
    const glm::mat4 p = camera_.projection(float(width()) / float(height()));
    const glm::vec2 jitter = sampler_.jitter();
    if (jitter == glm::vec2(0.0f)) return p;
    // Shifting NDC by -2 j / size puts the point that was at pixel centre + j onto the pixel centre.
    const glm::vec3 shift(-2.0f * jitter.x / float(width()), -2.0f * jitter.y / float(height()), 0.0f);
    return glm::translate(glm::mat4(1.0f), shift) * p;
}

void Frame::accumulate(PassTimers& timers, bool progressive)
{
    if (sampler_.stillIndex() < 1) return;
    if (!accumulated_) accumulated_ = Texture::create2D("accumulated", GL_RGBA32F, settings_.width, settings_.height);
    PassCost cost;
    cost.flops = 8;
    cost.fetches = progressive ? 3 : 1;
    cost.bytesRead = progressive ? 64 : 32;
    cost.bytesWritten = progressive ? 48 : 16;
    auto t = timers.scope("accumulate", cost);
    t.expectComputes(computeInvocations({settings_.width, settings_.height, 1}, {8, 8, 1}));
    Program& program = progressive ? accumulateDirectProgram_ : accumulateProgram_;
    (progressive ? full_.direct : result()).bind(UNIT_COMPOSITE_DIRECT);
    accumulated_.bindImage(0, GL_READ_WRITE);
    if (progressive) {
        if (!accumulatedIndirect_)
            accumulatedIndirect_ =
                Texture::create2D("accumulated.indirect", GL_RGBA32F, settings_.width, settings_.height);
        full_.indirect.bind(UNIT_COMPOSITE_INDIRECT);
        composite_.bindImage(1, GL_WRITE_ONLY);
        accumulatedIndirect_.bindImage(2, GL_READ_WRITE);
        compositeUsed_ = true;
    }
    program.set("stillFrame", sampler_.stillIndex());
    dispatchCompute(program, glm::ivec3(settings_.width, settings_.height, 1), glm::ivec3(8, 8, 1));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    accumulatedResult_ = !progressive;
}

void Frame::antialiasEdges(PassTimers& timers)
{
    edgeAAUsed_ = false;
    if (!settings_.edgeAntialias || sampler_.stillIndex() != 0) return;
    if (!edgeAA_) edgeAA_ = std::make_unique<EdgeAntialias>();
    edgeAA_->run(*this, result(), timers);
    edgeAAUsed_ = true;
}

// What the frame's passes do per invocation (PassCost, timer.h), counted from their shaders. Bytes are
// render-target and G-buffer traffic; material blocks and uniforms stay in cache and are not counted.
namespace {

constexpr double kVertexBytes = sizeof(GpuVertex);

PassCost shadowCost(const GpuScene& scene, const ShadowMaps& shadows)
{
    PassCost c;
    c.bytesRead = 4; // depth test
    c.bytesWritten = 4;
    const double views = double(shadows.renderedViewCount());
    c.triangles = views * double(scene.triangleCount());
    c.bytesFixed = shadows.renderedTexels() * 4 + views * 3.0 * scene.triangleCount() * kVertexBytes;
    return c;
}

} // namespace

void Frame::renderShadowMaps(PassTimers& timers)
{
    // The direct pass reads no map in its still form with shadow rays (RAY_SHADOWS): where the technique
    // reads none either, none is drawn. On cornell-area at 256x256 the emitter's cube took 6.85 ms of
    // direct's 16.7 ms still frame (llvmpipe).
    const bool directReads = !(directPassStill() && settings_.stillRayShadows);
    shadows_.setRendered(shadowMapsRead_ || directReads);
    shadows_.fitTo(camera_, settings_.width, settings_.height);
    shadows_.setStill(sampler_.sampleIndex());
    auto t = timers.scope("shadow", shadowCost(gpu_, shadows_));
    shadows_.render(gpu_);
}

void Frame::renderGBuffer(PassTimers& timers)
{
    Targets& t = targets();
    // gbuffer.frag per fragment: eye depth and octahedral normal (8 bytes), diffuse (8), and where the
    // scene has them specular (8) and emission (8); the depth test reads and writes 4.
    const double targetBytes = 8 + 8 + (t.specular ? 8 : 0) + (t.emission ? 8 : 0);
    PassCost cost;
    cost.flops = 50; // normalize, brdfParams, the back-face case, the octahedral map
    // One bilinear base-colour sample, and one of the normal map where the pass bends normals.
    cost.fetches = (gpu_.hasTextures() ? 4 : 0) + (settings_.normalMaps && gpu_.hasNormalMaps() ? 4 : 0);
    cost.bytesRead = 4; // depth test
    cost.bytesWritten = targetBytes + 4;
    const double pixels = double(t.width) * t.height;
    cost.bytesFixed = pixels * (targetBytes + 4) + 3.0 * gpu_.triangleCount() * kVertexBytes; // clears, vertices
    cost.triangles = double(gpu_.triangleCount());
    auto timer = timers.scope("gbuffer", cost);
    updateGBufferCamera();
    PassState state = PassState::fullscreen(t.gbufferFbo, t.width, t.height);
    state.depthTest = true; // no culling: back faces of one-sided surfaces are drawn black (gbuffer.frag)
    state.apply();          // before the clears, which obey the write masks
    const GLuint zeroBits[4] = {0, 0, 0, 0};
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferuiv(t.gbufferFbo.id(), GL_COLOR, 0, zeroBits); // eye depth 0: background
    glClearNamedFramebufferfv(t.gbufferFbo.id(), GL_COLOR, 1, zero);
    if (t.specular) glClearNamedFramebufferfv(t.gbufferFbo.id(), GL_COLOR, 2, zero);
    if (t.emission) glClearNamedFramebufferfv(t.gbufferFbo.id(), GL_COLOR, 3, zero);
    glClearNamedFramebufferfi(t.gbufferFbo.id(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
    gbufferProgram_.set("viewProj", projection() * view());
    gbufferProgram_.set("view", view());
    // The eye-space ray through pixel centre c (gl_FragCoord.xy) is ((2 c / size - 1 + P[2].xy) / diag(P), -1)
    // (P[2].xy: the still frame's jitter): the same ray updateGBufferCamera gives in world space.
    const glm::mat4 p = projection();
    gbufferProgram_.set("eyeRay", glm::vec4(2.0f / (float(t.width) * p[0][0]), 2.0f / (float(t.height) * p[1][1]),
                                            (p[2][0] - 1.0f) / p[0][0], (p[2][1] - 1.0f) / p[1][1]));
    gpu_.materials().bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MATERIALS);
    gpu_.baseColorTextures().bind(UNIT_BASE_COLOR);
    gpu_.normalTextures().bind(UNIT_NORMAL_MAP);
    gbufferProgram_.draw(gpu_);
}

void Frame::updateGBufferCamera()
{
    Targets& t = targets();
    // The eye axes from the very matrices the G-buffer was rasterised with: row r of the view matrix is
    // eye axis r in world space, and the projection's diagonal holds 1 / tan of the half field of view.
    const glm::mat4 v = view(), p = projection();
    const glm::vec3 right(v[0][0], v[1][0], v[2][0]), up(v[0][1], v[1][1], v[2][1]);
    const glm::vec3 forward = -glm::vec3(v[0][2], v[1][2], v[2][2]);
    const glm::vec3 x = right / p[0][0], y = up / p[1][1]; // half the image, one metre ahead
    // NDC (u, v) is the eye direction forward + (u + P[2][0]) x + (v + P[2][1]) y: the jitter's offset
    // (projection()) is in P[2][0] and P[2][1], zero without it.
    GBufferCamera c;
    c.origin = glm::vec4(camera_.position, 1.0f);
    c.corner = glm::vec4(forward + (p[2][0] - 1.0f) * x + (p[2][1] - 1.0f) * y, 0.0f);
    c.axisX = glm::vec4(2.0f * x / float(t.width), 0.0f);
    c.axisY = glm::vec4(2.0f * y / float(t.height), 0.0f);
    c.present = glm::ivec4(t.specular ? 1 : 0, t.emission ? 1 : 0, 0, 0);
    t.camera.update(0, sizeof c, &c);
}

std::vector<Define> Frame::gbufferDefines() const
{
    return sceneDefines(scene_, gpu_);
}

bool Frame::directLightStill() const
{
    return sampler_.sampleIndex() > 0 && stillFormDiffers(gpu_, settings_, true);
}

std::vector<Define> Frame::directLightDefines(bool still) const
{
    return directLightKinds(gpu_, settings_, still, true);
}

std::vector<Define> Frame::shadowRayDefines() const
{
    return bounce::gl::shadowRayDefines(gpu_, settings_);
}

void Frame::setDirectLightUniforms(Program& program) const
{
    program.set("punctualLightCount", gpu_.punctualLightCount());
    program.set("lightCount", lights_.count());
    shadows_.setPcfUniforms(program, settings_.pcfRadius);
    if (sampler_.sampleIndex() > 0) {
        // The glossy lobe's points, independent of the jitter and the sample point.
        program.set("areaRotation",
                    FrameSampler::sample2(SampleStream::AreaGlossyRotation, std::uint64_t(sampler_.sampleIndex())));
    }
}

void Frame::bindGBuffer() const
{
    const Targets& t = targets();
    t.geometry.bind(UNIT_G_GEOMETRY);
    t.diffuse.bind(UNIT_G_DIFFUSE);
    (t.specular ? t.specular : black_).bind(UNIT_G_SPECULAR);
    (t.emission ? t.emission : black_).bind(UNIT_G_EMISSION);
    t.camera.bindBase(GL_UNIFORM_BUFFER, UBO_GBUFFER_CAMERA);
}

void Frame::bindSceneData() const
{
    gpu_.materials().bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MATERIALS);
    gpu_.bindGeometry();
    lights_.bind();
    shadows_.bind();
    // The still frames' shadow rays walk the frame's BVH (common/shadow.glsl, RAY_SHADOWS): every pass that
    // lights points with the frame's estimator binds the scene data, so it gets the BVH too.
    if (settings_.stillRayShadows && !gpu_.lights().empty()) rayCaster().bind();
}

void Frame::drawFullscreen() const
{
    emptyVao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void Frame::renderDirect(PassTimers& timers)
{
    drawDirect(timers);
    if (directSubsamplesPending_ > 1 && !coarseActive_) runDirectSamples(timers, true, false);
    directSubsamplesPending_ = 0;
}

void Frame::drawDirect(PassTimers& timers)
{
    Targets& t = targets();
    // direct.frag per pixel: two to four G-buffer texels (the targets the scene has), one target, and the
    // loop over the lights.
    const double punctual = gpu_.punctualLightCount(), area = areaLightsInDirect_ ? lights_.count() - punctual : 0.0;
    const PassCost lights = directLightsCost(*this, punctual, area);
    PassCost cost;
    cost.flops = 30 + lights.flops;
    cost.fetches = 2 + (t.specular ? 1 : 0) + (t.emission ? 1 : 0) + lights.fetches;
    cost.bytesRead = 8 + 8 + (t.specular ? 8 : 0) + (t.emission ? 8 : 0) + lights.bytesRead;
    cost.bytesWritten = 16;
    auto timer = timers.scope("direct", cost);
    timer.expectFragments(t.width, t.height);
    PassState::fullscreen(t.directFbo, t.width, t.height).apply();
    bindGBuffer();
    bindSceneData();
    const bool still = directPassStill();
    // A moving frame with the reuse of its direct light, at the frame's own size: the ratio estimator's form.
    const bool ratio = still && sampler_.stillIndex() == 0 && directRatioProgram_ && !coarseActive_;
    if (!coarseActive_) areaRatioDrawn_ = ratio;
    if (ratio) {
        allocateAreaRatio();
        PassState::fullscreen(areaRatio_.fbo, t.width, t.height).apply();
    }
    Program& program = ratio ? directRatioProgram_ : still ? directStillProgram_ : directProgram_;
    program.set("cameraPosition", camera_.position);
    setDirectLightUniforms(program);
    program.use();
    drawFullscreen();
}

void Frame::renderDirectSubsamples(PassTimers& timers)
{
    directSubsamplesPending_ = 0;
    const int n = sampler_.stillIndex() >= 1 ? settings_.stillDirectSamples : settings_.movingDirectSamples;
    if (n < 2 || coarseActive_) return;
    if (!directSum_ || directSum_.width() != full_.width || directSum_.height() != full_.height)
        directSum_ = Texture::create2D("direct.sum", GL_RGBA32F, full_.width, full_.height);
    for (int k = 1; k < n; ++k) {
        sampler_.setDirectSubsample(k, n);
        renderGBuffer(timers);
        drawDirect(timers);
        runDirectSamples(timers, false, k == 1);
    }
    sampler_.setDirectSubsample(0, n); // the frame's own point, where the technique gathers
    directSubsamplesPending_ = n;
}

void Frame::runDirectSamples(PassTimers& timers, bool resolve, bool first)
{
    Program& program = resolve ? directMeanProgram_ : directSumProgram_;
    if (!program)
        program = Program::compute(resolve ? "direct.samples.mean" : "direct.samples.sum", "frame/direct_samples.comp",
                                   resolve ? std::vector<Define>{{"RESOLVE", "1"}} : std::vector<Define>{});
    PassCost cost;
    cost.flops = 4;
    cost.bytesRead = first && !resolve ? 16 : 32;
    cost.bytesWritten = 16;
    auto t = timers.scope("direct.samples", cost);
    t.expectComputes(computeInvocations({full_.width, full_.height, 1}, {8, 8, 1}));
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    full_.direct.bindImage(0, resolve ? GL_READ_WRITE : GL_READ_ONLY);
    directSum_.bindImage(1, resolve ? GL_READ_ONLY : GL_READ_WRITE);
    program.set("first", first ? 1 : 0);
    program.set("scale", 1.0f / float(std::max(directSubsamplesPending_, 1)));
    dispatchCompute(program, glm::ivec3(full_.width, full_.height, 1), glm::ivec3(8, 8, 1));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

void Frame::allocateAreaRatio()
{
    AreaRatio& r = areaRatio_;
    if (r.unshadowed && r.unshadowed.width() == full_.width && r.unshadowed.height() == full_.height &&
        r.direct == full_.direct.id())
        return;
    r.unshadowed = Texture::create2D("direct.areaUnshadowed", GL_RGBA32F, full_.width, full_.height);
    r.visibility = Texture::create2D("direct.areaVisibility", GL_RGBA32F, full_.width, full_.height);
    r.fbo = Framebuffer("direct.ratio.fbo");
    r.fbo.attach(GL_COLOR_ATTACHMENT0, full_.direct);
    r.fbo.attach(GL_COLOR_ATTACHMENT1, r.unshadowed);
    r.fbo.attach(GL_COLOR_ATTACHMENT2, r.visibility);
    r.fbo.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2});
    r.fbo.checkComplete();
    r.direct = full_.direct.id();
    if (!r.resolve)
        r.resolve = Program::graphics("direct.ratio.resolve", "frame/fullscreen.vert", "frame/direct_ratio.frag");
}

void Frame::resolveAreaRatio(PassTimers& timers)
{
    if (!areaRatioDrawn_) return;
    PassCost cost;
    cost.flops = 8;
    cost.fetches = 2;
    cost.bytesRead = 32 + 16; // the two inputs, and the blend's read of the direct light
    cost.bytesWritten = 16;
    auto t = timers.scope("direct.ratio", cost);
    t.expectFragments(full_.width, full_.height);
    PassState state = PassState::fullscreen(full_.directFbo, full_.width, full_.height);
    state.blend = true; // one, one: the direct pass's other light plus the emitters' share
    state.apply();
    areaRatio_.unshadowed.bind(UNIT_AREA_UNSHADOWED);
    areaRatio_.visibility.bind(UNIT_AREA_VISIBILITY);
    areaRatio_.resolve.use();
    drawFullscreen();
}

void Frame::clearIndirect()
{
    const float zero[4] = {0, 0, 0, 0};
    targets().indirect.clear(0, zero);
}

void Frame::composite(PassTimers& timers, bool withIndirect)
{
    compositeUsed_ = withIndirect;
    if (!withIndirect) return; // direct + nothing: the direct texture is the result
    PassCost cost;
    cost.flops = 4;
    cost.fetches = 2;
    cost.bytesRead = 32;
    cost.bytesWritten = 16;
    auto t = timers.scope("composite", cost);
    t.expectFragments(full_.width, full_.height);
    PassState::fullscreen(compositeFbo_, full_.width, full_.height).apply();
    full_.direct.bind(UNIT_COMPOSITE_DIRECT);
    full_.indirect.bind(UNIT_COMPOSITE_INDIRECT);
    compositeProgram_.use();
    drawFullscreen();
}

std::vector<float> Frame::decode(int output) const
{
    Texture target = Texture::create2D("gbuffer.decoded", GL_RGBA32F, width(), height());
    Framebuffer fbo("gbuffer.decode.fbo");
    fbo.attach(GL_COLOR_ATTACHMENT0, target);
    fbo.checkComplete();
    Program decoder = Program::graphics("gbuffer.decode", "frame/fullscreen.vert", "frame/gbuffer_decode.frag");
    PassState::fullscreen(fbo, width(), height()).apply();
    bindGBuffer();
    decoder.set("decodeNormals", output);
    decoder.use();
    drawFullscreen();
    return target.readFloats(0, 4);
}

std::vector<float> Frame::readPositions() const
{
    return decode(0);
}

std::vector<float> Frame::readNormals() const
{
    return decode(1);
}

core::Image Frame::readEmission() const
{
    if (targets().emission) return read(targets().emission);
    return core::Image(width(), height());
}

namespace {

// Four floats per pixel in GL rows (row 0 at the bottom) as an RGB image with row 0 at the top.
core::Image rgbaToImage(const std::vector<float>& rgba, int width, int height)
{
    core::Image img(width, height);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float* p = &rgba[(std::size_t(img.height - 1 - y) * img.width + x) * 4]; // GL rows go up
            img.set(x, y, {p[0], p[1], p[2]});
        }
    return img;
}

} // namespace

core::Image Frame::read(const Texture& texture) const
{
    return rgbaToImage(texture.readFloats(0, 4), texture.width(), texture.height());
}

core::Image Frame::toImage(const std::vector<float>& rgba) const
{
    return rgbaToImage(rgba, width(), height());
}

} // namespace bounce::gl
