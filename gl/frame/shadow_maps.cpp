#include "gl/frame/shadow_maps.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "gl/frame/bindings.h"
#include "gl/gl.h"
#include "gl/resource/pass_state.h"

namespace bounce::gl {

namespace {

struct GpuShadowView {
    glm::mat4 viewProj;
    glm::vec4 originFar;
    glm::vec4 texelWorld;
};

} // namespace

ShadowMaps::ShadowMaps(const GpuScene& scene, int size)
    : size_(size), fbo_("shadow.fbo"), program_("shadow", "frame/shadow.vert", "frame/shadow.frag")
{
    program_.prepare(scene);
    update(scene);
}

void ShadowMaps::buildViews(const GpuScene& scene)
{
    views_.clear();
    gpuLights_.clear();
    std::vector<glm::vec4> polygons;
    // 2% wider than the spot's cone so that PCF taps at its edge stay inside the map.
    const LightViews lv = buildLightViews(scene.lights(), scene.bounds(), {.fovMargin = 1.02f});
    for (const LightView& l : lv.views) {
        ShadowView v;
        v.view = l.view;
        v.proj = l.proj;
        v.origin = l.origin;
        v.far = l.far;
        v.texelWorld = l.orthographic ? 2.0f * l.orthoHalfExtent / float(size_)
                       : l.cubeFace   ? 2.0f / float(size_)
                                      : 2.0f * std::tan(0.5f * l.fovRad) / float(size_);
        views_.push_back(v);
    }
    for (std::size_t i = 0; i < scene.lights().size(); ++i) {
        const LightSource& s = scene.lights()[i];
        GpuLight g;
        g.positionType = glm::vec4(s.position, float(s.type));
        g.directionCosOuter = glm::vec4(s.direction, s.cosOuter);
        g.intensityCosInner = glm::vec4(s.intensity, s.cosInner);
        const glm::ivec2 layers =
            i < lv.lightViews.size() ? lv.lightViews[i] : glm::ivec2(-1, 0); // no geometry: unshadowed
        g.shadow = glm::ivec4(layers.x, layers.y, -1, 0);
        if (s.type == kLightArea) {
            g.shadow.z = int(polygons.size());
            for (const glm::vec3& p : s.triangle) polygons.emplace_back(p, 1.0f);
        }
        gpuLights_.push_back(g);
    }
    std::vector<GpuShadowView> gv;
    for (const ShadowView& v : views_)
        gv.push_back({v.proj * v.view, glm::vec4(v.origin, v.far), glm::vec4(v.texelWorld, 0, 0, 0)});
    if (gv.empty()) gv.push_back({});
    if (polygons.empty()) polygons.emplace_back(0.0f);
    std::vector<GpuLight> lights = gpuLights_;
    if (lights.empty()) lights.push_back({});
    lightsBuffer_ = Buffer::fromVector("lights", lights);
    viewsBuffer_ = Buffer::fromVector("shadow.views", gv);
    polygonsBuffer_ = Buffer::fromVector("lights.polygons", polygons);
}

void ShadowMaps::update(const GpuScene& scene)
{
    buildViews(scene);
    const int layers = std::max(1, int(views_.size()));
    if (!depth_ || depth_.layers() != layers) {
        // A scene without lights still gets one 1x1 layer so the sampler has something to read.
        const int s = views_.empty() ? 1 : size_;
        depth_ = Texture::create2DArray("shadow.depth", GL_DEPTH_COMPONENT32F, s, s, layers);
        depth_.setCompare(true);
        setPcf(linear_);
        const float one[4] = {1, 1, 1, 1};
        depth_.clear(0, one);
    }
}

void ShadowMaps::setPcf(bool hardwareFilter)
{
    linear_ = hardwareFilter;
    if (depth_) depth_.setFilter(hardwareFilter ? GL_LINEAR : GL_NEAREST, hardwareFilter ? GL_LINEAR : GL_NEAREST);
}

void ShadowMaps::setPcfUniforms(Program& program, int radius) const
{
    program.set("pcfRadius", radius);
    program.set("pcfNearest", linear_ ? 0 : 1);
}

void ShadowMaps::render(const GpuScene& scene)
{
    if (views_.empty()) return;
    PassState state = PassState::fullscreen(fbo_, size_, size_);
    state.depthTest = true; // no culling: every surface blocks light from both sides
    state.polygonOffset = {1.0f, 1.0f};
    state.apply();
    if (scene.hasAlphaMask()) { // shadow.frag cuts the masks' holes
        scene.materials().bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MATERIALS);
        scene.baseColorTextures().bind(UNIT_BASE_COLOR);
    }
    for (std::size_t i = 0; i < views_.size(); ++i) {
        fbo_.attachLayer(GL_DEPTH_ATTACHMENT, depth_, int(i));
        glNamedFramebufferDrawBuffer(fbo_.id(), GL_NONE);
        glClear(GL_DEPTH_BUFFER_BIT);
        program_.set("viewProj", views_[i].proj * views_[i].view);
        program_.draw(scene);
    }
}

void ShadowMaps::bind() const
{
    lightsBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_LIGHTS);
    viewsBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SHADOW_VIEWS);
    polygonsBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_LIGHT_POLYGONS);
    depth_.bind(UNIT_SHADOW_MAPS);
}

} // namespace bounce::gl
