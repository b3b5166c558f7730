#include "gl/frame/shadow_maps.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "gl/gl.h"

namespace bounce::gl {

namespace {

struct GpuShadowView {
    glm::mat4 viewProj;
    glm::vec4 originFar;
    glm::vec4 texelWorld;
};

} // namespace

void lightNearFar(const core::Bounds& b, const glm::vec3& origin, float& near, float& far)
{
    float maxDist = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 c(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
        maxDist = std::max(maxDist, glm::length(c - origin));
    }
    far = std::max(maxDist * 1.01f, 1e-3f);
    near = std::max(far * 1e-4f, 1e-5f);
}

glm::vec3 lightUpVector(const glm::vec3& d) { return std::abs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0); }

std::vector<ShadowView> cubeViews(const glm::vec3& origin, float near, float far, int size)
{
    static const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    std::vector<ShadowView> v(6);
    for (int f = 0; f < 6; ++f) {
        v[f].view = glm::lookAt(origin, origin + dirs[f], ups[f]);
        v[f].proj = glm::perspective(glm::radians(90.0f), 1.0f, near, far);
        v[f].origin = origin;
        v[f].far = far;
        v[f].texelWorld = 2.0f / float(size);
    }
    return v;
}

ShadowMaps::ShadowMaps(const GpuScene& scene, int size)
    : size_(size), fbo_("shadow.fbo"), program_(Program::graphics("shadow", "frame/shadow.vert", "frame/shadow.frag"))
{
    update(scene);
}

void ShadowMaps::buildViews(const GpuScene& scene)
{
    views_.clear();
    gpuLights_.clear();
    std::vector<glm::vec4> polygons;
    std::vector<std::pair<int, int>> groupLayer; // area mesh -> first layer of its cube
    const core::Bounds& b = scene.bounds();
    for (const LightSource& s : scene.lights()) {
        GpuLight g;
        g.positionType = glm::vec4(s.position, float(s.type));
        g.directionCosOuter = glm::vec4(s.direction, s.cosOuter);
        g.intensityCosInner = glm::vec4(s.intensity, s.cosInner);
        g.shadow = glm::ivec4(int(views_.size()), 1, -1, 0);
        float near = 0.0f, far = 0.0f;
        if (s.type == kLightSpot && s.outerConeRad <= glm::radians(60.0f)) {
            lightNearFar(b, s.position, near, far);
            ShadowView v;
            const float fov = std::min(2.0f * s.outerConeRad * 1.02f, glm::radians(170.0f));
            v.view = glm::lookAt(s.position, s.position + s.direction, lightUpVector(s.direction));
            v.proj = glm::perspective(fov, 1.0f, near, far);
            v.origin = s.position;
            v.far = far;
            v.texelWorld = 2.0f * std::tan(0.5f * fov) / float(size_);
            views_.push_back(v);
        } else if (s.type == kLightDirectional) {
            const glm::vec3 c = b.centre();
            const float r = std::max(0.5f * glm::length(b.extent()), 1e-3f);
            ShadowView v;
            v.view = glm::lookAt(c - s.direction * (2.0f * r), c, lightUpVector(s.direction));
            v.proj = glm::ortho(-r, r, -r, r, 0.0f, 4.0f * r);
            v.origin = c - s.direction * (2.0f * r);
            v.far = 0.0f;
            v.texelWorld = 2.0f * r / float(size_);
            views_.push_back(v);
        } else if (s.type == kLightArea) {
            g.shadow.z = int(polygons.size());
            for (const glm::vec3& p : s.triangle) polygons.emplace_back(p, 1.0f);
            const auto it = std::find_if(groupLayer.begin(), groupLayer.end(),
                                         [&](const auto& gl) { return gl.first == s.group; });
            if (it != groupLayer.end()) {
                g.shadow.x = it->second;
                g.shadow.y = 6;
            } else {
                groupLayer.emplace_back(s.group, int(views_.size()));
                lightNearFar(b, s.position, near, far);
                const auto cube = cubeViews(s.position, near, far, size_);
                views_.insert(views_.end(), cube.begin(), cube.end());
                g.shadow.y = 6;
            }
        } else { // point light, or a spot too wide for one perspective view
            lightNearFar(b, s.position, near, far);
            const auto cube = cubeViews(s.position, near, far, size_);
            views_.insert(views_.end(), cube.begin(), cube.end());
            g.shadow.y = 6;
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

void ShadowMaps::render(const GpuScene& scene)
{
    if (views_.empty()) return;
    fbo_.bind();
    glViewport(0, 0, size_, size_);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE); // every surface blocks light from both sides
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    program_.use();
    for (std::size_t i = 0; i < views_.size(); ++i) {
        fbo_.attachLayer(GL_DEPTH_ATTACHMENT, depth_, int(i));
        glNamedFramebufferDrawBuffer(fbo_.id(), GL_NONE);
        glClear(GL_DEPTH_BUFFER_BIT);
        program_.set("viewProj", views_[i].proj * views_[i].view);
        scene.draw();
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
}

void ShadowMaps::bind() const
{
    lightsBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    viewsBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, 2);
    polygonsBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, 3);
    depth_.bind(5);
}

} // namespace bounce::gl
