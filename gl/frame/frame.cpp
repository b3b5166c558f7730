#include "gl/frame/frame.h"

#include "gl/frame/bindings.h"
#include "gl/frame/frame_budget.h"
#include "gl/gl.h"
#include "gl/resource/pass_state.h"

namespace bounce::gl {

namespace {

// The direct-light program for the kinds of light the scene has: a loop over a kind the scene lacks
// still costs a masked pass through its body on a SIMD rasteriser (llvmpipe), the polygon form factor
// of the emitting triangles most of all (glsl/common/lighting.glsl).
Program directProgram(const GpuScene& scene)
{
    std::vector<Define> kinds;
    if (scene.punctualLightCount() > 0) kinds.push_back({"PUNCTUAL_LIGHTS", "1"});
    if (int(scene.lights().size()) > scene.punctualLightCount()) kinds.push_back({"AREA_LIGHTS", "1"});
    return Program::graphics("direct", "frame/fullscreen.vert", "frame/direct.frag", kinds);
}

SceneProgram gbufferProgram(const GpuScene& scene, const FrameSettings& settings)
{
    std::vector<Define> defines;
    if (settings.gbufferConstantFragment) defines.push_back({"GBUFFER_CONSTANT_FRAGMENT", "1"});
    SceneProgram p("gbuffer", "frame/gbuffer.vert", "frame/gbuffer.frag", defines);
    p.prepare(scene);
    return p;
}

} // namespace

Frame::Frame(const core::Scene& scene, const FrameSettings& settings)
    : scene_(scene),
      settings_(settings),
      camera_(scene.camera),
      gpu_(scene, settings.textureSize),
      shadows_(gpu_, settings.shadowMapSize),
      gbufferFbo_("gbuffer.fbo"),
      directFbo_("direct.fbo"),
      compositeFbo_("composite.fbo"),
      emptyVao_("fullscreen"),
      gbufferProgram_(gbufferProgram(gpu_, settings)),
      directProgram_(directProgram(gpu_)),
      compositeProgram_(Program::graphics("composite", "frame/fullscreen.vert", "frame/composite.frag"))
{
    shadows_.setPcf(settings.pcfLinear);
    allocateTargets();
}

void Frame::allocateTargets()
{
    checkFrameFits(settings_); // before any target: a size the driver cannot hold stops the run at once
    const int w = settings_.width, h = settings_.height;
    position_ = Texture::create2D("gbuffer.position", GL_RGBA32F, w, h);
    normal_ = Texture::create2D("gbuffer.normal", GL_RGBA32F, w, h);
    diffuse_ = Texture::create2D("gbuffer.diffuse", GL_RGBA16F, w, h);
    specular_ = Texture::create2D("gbuffer.specular", GL_RGBA16F, w, h);
    emission_ = Texture::create2D("gbuffer.emission", GL_RGBA16F, w, h);
    depth_ = Texture::create2D("gbuffer.depth", GL_DEPTH_COMPONENT32F, w, h);
    direct_ = Texture::create2D("direct", GL_RGBA32F, w, h);
    indirect_ = Texture::create2D("indirect", GL_RGBA32F, w, h);
    composite_ = Texture::create2D("composite", GL_RGBA32F, w, h);
    gbufferFbo_.attach(GL_COLOR_ATTACHMENT0, position_);
    gbufferFbo_.attach(GL_COLOR_ATTACHMENT1, normal_);
    gbufferFbo_.attach(GL_COLOR_ATTACHMENT2, diffuse_);
    gbufferFbo_.attach(GL_COLOR_ATTACHMENT3, specular_);
    gbufferFbo_.attach(GL_COLOR_ATTACHMENT4, emission_);
    gbufferFbo_.attach(GL_DEPTH_ATTACHMENT, depth_);
    gbufferFbo_.setDrawBuffers(
        {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4});
    gbufferFbo_.checkComplete();
    directFbo_.attach(GL_COLOR_ATTACHMENT0, direct_);
    directFbo_.checkComplete();
    compositeFbo_.attach(GL_COLOR_ATTACHMENT0, composite_);
    compositeFbo_.checkComplete();
    clearIndirect();
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
    const int punctualBefore = gpu_.punctualLightCount();
    gpu_.setLights(lights);
    shadows_.update(gpu_);
    ++version_.lights;
    if ((punctualBefore > 0) != (gpu_.punctualLightCount() > 0)) directProgram_ = directProgram(gpu_);
}

void Frame::resize(int width, int height)
{
    if (width == settings_.width && height == settings_.height) return;
    settings_.width = width;
    settings_.height = height;
    allocateTargets();
    ++version_.camera;
}

void Frame::beginFrame()
{
    ++frameIndex_;
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
    const double views = double(shadows.views().size());
    c.triangles = views * double(scene.triangleCount());
    c.bytesFixed = views * (double(shadows.size()) * shadows.size() * 4 + 3.0 * scene.triangleCount() * kVertexBytes);
    return c;
}

} // namespace

void Frame::renderShadowMaps(PassTimers& timers)
{
    auto t = timers.scope("shadow", shadowCost(gpu_, shadows_));
    shadows_.render(gpu_);
}

void Frame::renderGBuffer(PassTimers& timers)
{
    PassCost cost;
    cost.flops = 40;                           // gbuffer.frag: normalize, brdfParams, the back-face case
    cost.fetches = gpu_.hasTextures() ? 4 : 0; // one bilinear base-colour sample
    cost.bytesRead = 4;                        // depth test
    cost.bytesWritten = 2 * 16 + 3 * 8 + 4;    // two RGBA32F and three RGBA16F targets, depth
    const double pixels = double(settings_.width) * settings_.height;
    cost.bytesFixed = pixels * (2 * 16 + 3 * 8 + 4) + 3.0 * gpu_.triangleCount() * kVertexBytes; // clears, vertices
    cost.triangles = double(gpu_.triangleCount());
    auto t = timers.scope("gbuffer", cost);
    PassState state = PassState::fullscreen(gbufferFbo_, settings_.width, settings_.height);
    state.depthTest = true; // no culling: back faces of one-sided surfaces are drawn black (gbuffer.frag)
    state.apply();          // before the clears, which obey the write masks
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < 5; ++i) glClearNamedFramebufferfv(gbufferFbo_.id(), GL_COLOR, i, zero);
    glClearNamedFramebufferfi(gbufferFbo_.id(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
    gbufferProgram_.set("viewProj", projection() * view());
    gbufferProgram_.set("view", view());
    gpu_.materials().bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MATERIALS);
    gpu_.baseColorTextures().bind(UNIT_BASE_COLOR);
    gbufferProgram_.draw(gpu_);
}

void Frame::bindGBuffer() const
{
    position_.bind(UNIT_G_POSITION);
    normal_.bind(UNIT_G_NORMAL);
    diffuse_.bind(UNIT_G_DIFFUSE);
    specular_.bind(UNIT_G_SPECULAR);
    emission_.bind(UNIT_G_EMISSION);
}

void Frame::bindSceneData() const
{
    gpu_.materials().bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MATERIALS);
    gpu_.bindGeometry();
    shadows_.bind();
}

void Frame::drawFullscreen() const
{
    emptyVao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void Frame::renderDirect(PassTimers& timers)
{
    // direct.frag per pixel: five G-buffer texels, one target; per punctual light about 60 flops and
    // (2r+1)^2 shadow taps (four texels each when filtered), per emitting triangle about 250 flops (the
    // clipped polygon's form factor) and its shadow taps.
    const double taps =
        double((2 * settings_.pcfRadius + 1) * (2 * settings_.pcfRadius + 1)) * (settings_.pcfLinear ? 4.0 : 1.0);
    const double punctual = gpu_.punctualLightCount(), area = shadows_.lightCount() - punctual;
    PassCost cost;
    cost.flops = 30 + punctual * (60 + 10 * taps) + area * (250 + 10 * taps);
    cost.fetches = 5 + (punctual + area) * taps;
    cost.bytesRead = 2 * 16 + 3 * 8 + (punctual + area) * taps * 4;
    cost.bytesWritten = 16;
    auto t = timers.scope("direct", cost);
    PassState::fullscreen(directFbo_, settings_.width, settings_.height).apply();
    bindGBuffer();
    bindSceneData();
    directProgram_.set("cameraPosition", camera_.position);
    directProgram_.set("punctualLightCount", gpu_.punctualLightCount());
    directProgram_.set("lightCount", shadows_.lightCount());
    directProgram_.set("pcfRadius", settings_.pcfRadius);
    directProgram_.use();
    drawFullscreen();
}

void Frame::clearIndirect()
{
    const float zero[4] = {0, 0, 0, 0};
    indirect_.clear(0, zero);
}

void Frame::composite(PassTimers& timers)
{
    PassCost cost;
    cost.flops = 4;
    cost.fetches = 2;
    cost.bytesRead = 32;
    cost.bytesWritten = 16;
    auto t = timers.scope("composite", cost);
    PassState::fullscreen(compositeFbo_, settings_.width, settings_.height).apply();
    direct_.bind(UNIT_COMPOSITE_DIRECT);
    indirect_.bind(UNIT_COMPOSITE_INDIRECT);
    compositeProgram_.use();
    drawFullscreen();
}

core::Image Frame::read(const Texture& texture) const
{
    const std::vector<float> rgba = texture.readFloats(0, 4);
    core::Image img(texture.width(), texture.height());
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float* p = &rgba[(std::size_t(img.height - 1 - y) * img.width + x) * 4]; // GL rows go up
            img.set(x, y, {p[0], p[1], p[2]});
        }
    return img;
}

} // namespace bounce::gl
