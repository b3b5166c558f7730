#include "gl/frame/shadow_maps.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/sampling.h"
#include "gl/frame/bindings.h"
#include "gl/frame/frame_sampler.h"
#include "gl/gl.h"
#include "gl/resource/pass_state.h"

namespace bounce::gl {

namespace {} // namespace

ShadowMaps::ShadowMaps(const GpuScene& scene, FrameLights& lights, int size, int cascades, float footprint)
    : size_(size),
      footprint_(footprint),
      lights_(&lights),
      fbo_("shadow.fbo"),
      program_("shadow", "frame/shadow.vert", "frame/shadow.frag")
{
    fit_.cascades = cascades;
    program_.prepare(scene);
    update(scene);
}

void ShadowMaps::fitTo(const core::Camera& camera, int width, int height)
{
    const float aspect = float(width) / float(std::max(height, 1));
    const bool cascades = fit_.cascades > 0 && hasLightOfType(sources_, kLightDirectional);
    const bool footprints =
        footprint_ > 0.0f && (hasLightOfType(sources_, kLightSpot) || hasLightOfType(sources_, kLightPoint));
    const core::Camera& c = fit_.camera;
    const bool same = fitted_ && c.position == camera.position && c.forward == camera.forward && c.up == camera.up &&
                      c.yfovRad == camera.yfovRad && c.znear == camera.znear && fit_.aspect == aspect &&
                      height_ == height;
    if ((!cascades && !footprints) || same) return;
    fit_.camera = camera;
    fit_.aspect = aspect;
    height_ = height;
    fitted_ = true;
    if (cascades) lightViews_ = buildLightViews(sources_, bounds_, {.fovMargin = 1.02f, .fit = fit_});
    sides_ = footprintSides();
    upload();
}

std::vector<int> ShadowMaps::footprintSides() const
{
    std::vector<int> sides(lightViews_.views.size(), size_);
    if (footprint_ <= 0.0f || !fitted_) return sides;
    const int least = std::min(kMinFootprintSide, size_);
    for (std::size_t i = 0; i < sides.size(); ++i) {
        const LightView& v = lightViews_.views[i];
        if (v.orthographic || v.areaCount > 0) continue;
        float want = footprint_ * footprintSide(v, fit_, height_, bounds_);
        want = std::isfinite(want) ? std::clamp(want, 1.0f, float(size_)) : float(size_); // a camera gone wrong: whole
        sides[i] = std::clamp(int(std::bit_ceil(unsigned(std::ceil(want)))), least, size_);
    }
    return sides;
}

void ShadowMaps::buildViews(const GpuScene& scene)
{
    sources_ = scene.lights();
    bounds_ = scene.bounds();
    // 2% wider than the spot's cone so that PCF taps at its edge stay inside the map.
    lightViews_ = buildLightViews(sources_, bounds_, {.fovMargin = 1.02f, .fit = fit_});
    sides_ = footprintSides();
    areaGroups_.clear();
    for (const LightView& l : lightViews_.views)
        if (l.areaCount > 0 && (areaGroups_.empty() || areaGroups_.back().x != l.areaFirst))
            areaGroups_.emplace_back(l.areaFirst, l.areaCount);
    polygons_.clear();
    for (const LightSource& s : sources_)
        if (s.type == kLightArea)
            for (const glm::vec3& p : s.triangle) polygons_.emplace_back(p, 1.0f);
    upload();
}

namespace {

// The receiver's normal offset in still frames (texels), measured at 256x256 after 64 still frames, 4x4-block
// relative RMSE against the path tracer's direct light (cornell-spot / cornell-area / Sponza in the sun):
// 1.5 texels 4.6% / - / -, 0.5: 3.0% / 3.0% / 4.8% (128 frames), 0.25: 2.8% / 3.0% / 3.9%, 0: 2.7% / 3.0% /
// 3.8% with Sponza's mean 0.9% low (surfaces at a slant begin to shadow themselves). The polygon offset
// (slope-scaled, ShadowMaps::render) does the rest.
constexpr float kStillNormalOffset = 0.25f;

float triangleArea(const glm::vec3* t)
{
    return 0.5f * glm::length(glm::cross(t[1] - t[0], t[2] - t[0]));
}

// Still frame i's point on an emitting mesh: uniform by area, point i of the stream AreaLightPoint, a
// scrambled Sobol sequence (FrameSampler), the first coordinate choosing the triangle
// by its share of the area and then, rescaled, with the second the point inside it. Returns the triangle's
// light index. Halton's dimensions 2 and 3 were used before: bases 5 and 7, whose first points lie on lines
// (1/5, 1/7), (2/5, 2/7), ...; cornell-area's direct light at 256x256 after 16 frames was 9.4% from the
// path tracer's (4x4-block means), 5.1% with these points.
int areaSample(const std::vector<LightSource>& lights, glm::ivec2 group, int index, glm::vec3& point, float& area)
{
    area = 0.0f;
    for (int k = 0; k < group.y; ++k) area += triangleArea(lights[group.x + k].triangle);
    const glm::vec2 r = FrameSampler::sample2(SampleStream::AreaLightPoint, std::uint64_t(index));
    float u = r.x * area;
    const float v = r.y;
    int t = group.x + group.y - 1;
    for (int k = 0; k < group.y; ++k) {
        const float a = triangleArea(lights[group.x + k].triangle);
        if (u < a || k == group.y - 1) {
            t = group.x + k;
            u = a > 0.0f ? std::clamp(u / a, 0.0f, 1.0f) : 0.0f;
            break;
        }
        u -= a;
    }
    const glm::vec2 b = core::sampleUniformTriangle({u, v});
    const glm::vec3* tri = lights[t].triangle;
    point = tri[0] * (1.0f - b.x - b.y) + tri[1] * b.x + tri[2] * b.y;
    return t;
}

} // namespace

void ShadowMaps::setStill(int index)
{
    if (index == still_) return;
    still_ = index;
    upload();
}

void ShadowMaps::upload()
{
    std::vector<LightView> lv = lightViews_.views;
    std::vector<GpuLight> lights;
    for (const LightSource& s : sources_) {
        GpuLight g;
        g.position = s.position;
        g.type = s.type;
        g.direction = s.direction;
        g.cosOuter = s.cosOuter;
        g.intensity = s.intensity;
        g.cosInner = s.type == kLightArea ? 0.0f : s.cosInner;
        lights.push_back(g);
    }
    if (still_ > 0) {
        for (const glm::ivec2& group : areaGroups_) {
            glm::vec3 x;
            float area = 0.0f;
            const int t = areaSample(sources_, group, still_, x, area);
            for (int k = group.x; k < group.x + group.y; ++k) lights[k].position = x;
            lights[t].sampleArea = area;
            float near = 0.0f, far = 0.0f;
            lightNearFar(bounds_, x, near, far);
            const std::vector<LightView> cube = cubeViews(x, near, far);
            const int first = lightViews_.lightViews[std::size_t(group.x)].x;
            for (int f = 0; f < 6; ++f) {
                LightView& v = lv[std::size_t(first + f)];
                v.view = cube[f].view;
                v.proj = cube[f].proj;
                v.origin = x;
                v.far = far;
            }
        }
        // A sub-texel shift of every view (of its own side): the stream ShadowShift, less the texel's centre.
        const glm::vec2 shift = FrameSampler::sample2(SampleStream::ShadowShift, std::uint64_t(still_)) - 0.5f;
        for (std::size_t i = 0; i < lv.size(); ++i)
            lv[i].proj = glm::translate(glm::mat4(1.0f), glm::vec3(2.0f * shift / float(sides_[i]), 0.0f)) * lv[i].proj;
    }
    views_ = lv;
    int polygon = 0;
    for (std::size_t i = 0; i < sources_.size(); ++i) {
        const glm::ivec2 layers = i < lightViews_.lightViews.size() ? lightViews_.lightViews[i]
                                                                    : glm::ivec2(-1, 0); // no geometry: unshadowed
        lights[i].shadow = glm::ivec4(layers.x, layers.y, -1, 0);
        if (sources_[i].type == kLightArea) {
            lights[i].shadow.z = polygon;
            polygon += 3;
        }
    }
    std::vector<GpuShadowView> gv;
    for (std::size_t i = 0; i < views_.size(); ++i) {
        // A view of side s < size is rendered into the corner [0, s)^2 of its layer: its lookups map
        // [-1, 1] to that corner's share of the layer (x -> scale x + scale - 1).
        const LightView& v = views_[i];
        const float scale = float(sides_[i]) / float(size_);
        const glm::mat4 corner = glm::translate(glm::mat4(1.0f), glm::vec3(scale - 1.0f, scale - 1.0f, 0.0f)) *
                                 glm::scale(glm::mat4(1.0f), glm::vec3(scale, scale, 1.0f));
        gv.push_back(
            {corner * v.proj * v.view, glm::vec4(v.origin, v.far), glm::vec4(v.texelSide(sides_[i]), scale, 0, 0)});
    }
    // Still frames rewrite the same sizes in place.
    lights_->set(lights, gv, polygons_);
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
    // Still frames: one nearest tap from a map shifted by a sub-texel offset each frame, whose mean is the
    // hard shadow itself, where a filter's mean would stay as wide as its kernel.
    program.set("pcfRadius", still_ > 0 ? 0 : radius);
    program.set("pcfNearest", linear_ && still_ == 0 ? 0 : 1);
    program.set("shadowNormalOffset", still_ > 0 ? kStillNormalOffset : 1.5f);
}

void ShadowMaps::render(const GpuScene& scene)
{
    if (views_.empty()) return;
    PassState state = PassState::fullscreen(fbo_, size_, size_);
    state.depthTest = true; // no culling: every surface blocks light from both sides
    state.polygonOffset = {1.0f, 1.0f};
    if (scene.hasAlphaMask()) { // shadow.frag cuts the masks' holes
        scene.materials().bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MATERIALS);
        scene.baseColorTextures().bind(UNIT_BASE_COLOR);
    }
    for (std::size_t i = 0; i < views_.size(); ++i) {
        // A directional light's cascades are rendered (and read: SHADOW_CASCADES, the still frames' direct
        // pass) in still frames only: on llvmpipe three of them took Crytek Sponza's shadow pass at 1024x768
        // from 32 to 117 ms (vertex work and binning, once per view), and the moving frame must not get
        // slower. Moving frames, and every other pass, read the whole-scene view.
        if (!renders(i)) continue;
        // A view smaller than the layer: its corner only, cleared and drawn.
        state.viewport = glm::ivec4(0, 0, sides_[i], sides_[i]);
        state.scissor = sides_[i] < size_;
        state.apply();
        fbo_.attachLayer(GL_DEPTH_ATTACHMENT, depth_, int(i));
        glNamedFramebufferDrawBuffer(fbo_.id(), GL_NONE);
        glClear(GL_DEPTH_BUFFER_BIT);
        program_.set("viewProj", views_[i].proj * views_[i].view);
        program_.draw(scene);
    }
}

int ShadowMaps::renderedViewCount() const
{
    int n = 0;
    for (std::size_t i = 0; i < views_.size(); ++i) n += renders(i) ? 1 : 0;
    return n;
}

double ShadowMaps::renderedTexels() const
{
    double n = 0.0;
    for (std::size_t i = 0; i < views_.size(); ++i) n += renders(i) ? double(sides_[i]) * sides_[i] : 0.0;
    return n;
}

void SamplerDeleter::operator()(unsigned id) const
{
    glDeleteSamplers(1, &id);
}

void ShadowMaps::bind() const
{
    if (!rawSampler_) {
        unsigned id = 0;
        glCreateSamplers(1, &id);
        glSamplerParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_NONE);
        glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glSamplerParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glSamplerParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        rawSampler_ = Handle<SamplerDeleter>(id);
    }
    depth_.bind(UNIT_SHADOW_DEPTHS);
    glBindSampler(UNIT_SHADOW_DEPTHS, rawSampler_.id());
    depth_.bind(UNIT_SHADOW_MAPS);
}

} // namespace bounce::gl
