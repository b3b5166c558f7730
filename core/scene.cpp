#include "core/scene.h"

#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

namespace bounce::core {

float Light::spotWeight(float cosAngle) const
{
    if (type != LightType::Spot) return 1.0f;
    const float cosOuter = std::cos(outerConeRad);
    const float cosInner = std::cos(innerConeRad);
    if (innerConeRad >= outerConeRad || cosInner - cosOuter < 1e-6f) return cosAngle >= cosOuter ? 1.0f : 0.0f;
    const float t = glm::clamp((cosAngle - cosOuter) / (cosInner - cosOuter), 0.0f, 1.0f);
    return t * t;
}

glm::mat4 Camera::view() const
{
    return glm::lookAt(position, position + forward, up);
}

glm::mat4 Camera::projection(float aspect) const
{
    return glm::perspective(yfovRad, aspect, znear, zfar);
}

glm::vec3 Camera::rayDirection(float px, float py, int width, int height) const
{
    const float aspect = float(width) / float(height);
    const float tanHalf = std::tan(0.5f * yfovRad);
    const float sx = (2.0f * px / float(width) - 1.0f) * tanHalf * aspect;
    const float sy = (1.0f - 2.0f * py / float(height)) * tanHalf;
    const glm::vec3 right = glm::normalize(glm::cross(forward, up));
    return glm::normalize(forward + sx * right + sy * up);
}

Bounds Scene::bounds() const
{
    Bounds b;
    for (const Mesh& m : meshes)
        for (const glm::vec3& p : m.positions) b.extend(p);
    return b;
}

std::size_t Scene::triangleCount() const
{
    std::size_t n = 0;
    for (const Mesh& m : meshes) n += m.indices.size() / 3;
    return n;
}

bool Scene::hasEmission() const
{
    for (const Mesh& m : meshes)
        if (m.material < materials.size() && materials[m.material].isEmissive()) return true;
    return false;
}

bool Scene::hasGlossy() const
{
    for (const Mesh& m : meshes)
        if (m.material < materials.size() && materials[m.material].isGlossy()) return true;
    return false;
}

bool Scene::hasAlphaMask() const
{
    for (const Mesh& m : meshes)
        if (m.material < materials.size() && materials[m.material].isMasked()) return true;
    return false;
}

namespace {
struct Fnv1a {
    std::uint64_t h = 1469598103934665603ull;
    void bytes(const void* p, std::size_t n)
    {
        const auto* c = static_cast<const unsigned char*>(p);
        for (std::size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
    }
    template <class T>
    void pod(const T& v)
    {
        bytes(&v, sizeof v);
    }
    template <class T>
    void vec(const std::vector<T>& v)
    {
        pod(v.size());
        bytes(v.data(), v.size() * sizeof(T));
    }
};

bool finite(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
} // namespace

std::uint64_t Scene::contentHash() const
{
    Fnv1a f;
    f.pod(meshes.size());
    for (const Mesh& m : meshes) {
        f.vec(m.positions);
        f.vec(m.normals);
        f.vec(m.uvs);
        f.vec(m.indices);
        f.pod(m.material);
    }
    f.pod(materials.size());
    for (const Material& m : materials) {
        f.pod(m.baseColor);
        f.pod(m.baseColorTexture);
        f.pod(m.metallic);
        f.pod(m.roughness);
        f.pod(m.specular);
        f.pod(m.specularColor);
        f.pod(m.emission);
        f.pod(m.doubleSided);
        f.pod(m.alphaMode);
        f.pod(m.baseAlpha);
        f.pod(m.alphaCutoff);
    }
    f.pod(textures.size());
    for (const Texture& t : textures) {
        f.pod(t.width);
        f.pod(t.height);
        f.vec(t.rgba8);
    }
    f.pod(lights.size());
    for (const Light& l : lights) {
        f.pod(l.type);
        f.pod(l.position);
        f.pod(l.direction);
        f.pod(l.intensity);
        f.pod(l.innerConeRad);
        f.pod(l.outerConeRad);
    }
    return f.h;
}

void Scene::setVertices(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals)
{
    std::size_t count = 0;
    for (const Mesh& m : meshes) count += m.positions.size();
    if (count != positions.size() || count != normals.size())
        throw std::out_of_range("Scene::setVertices: vertex counts");
    std::size_t v = 0;
    for (Mesh& m : meshes)
        for (std::size_t i = 0; i < m.positions.size(); ++i, ++v) {
            m.positions[i] = positions[v];
            m.normals[i] = normals[v];
        }
}

std::string Scene::validate() const
{
    std::ostringstream err;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const Mesh& m = meshes[i];
        const std::string where = "mesh " + std::to_string(i) + " ('" + m.name + "')";
        if (m.indices.size() % 3 != 0)
            err << where << ": index count " << m.indices.size() << " is not a multiple of 3\n";
        if (m.normals.size() != m.positions.size())
            err << where << ": " << m.normals.size() << " normals for " << m.positions.size() << " positions\n";
        if (!m.uvs.empty() && m.uvs.size() != m.positions.size())
            err << where << ": uv count differs from position count\n";
        if (m.material >= materials.size()) err << where << ": material " << m.material << " out of range\n";
        for (std::uint32_t idx : m.indices)
            if (idx >= m.positions.size()) {
                err << where << ": index " << idx << " out of range (" << m.positions.size() << " positions)\n";
                break;
            }
        for (const glm::vec3& p : m.positions)
            if (!finite(p)) {
                err << where << ": non-finite (NaN/Inf) position\n";
                break;
            }
        for (const glm::vec3& n : m.normals)
            if (!finite(n)) {
                err << where << ": non-finite (NaN/Inf) normal\n";
                break;
            }
    }
    for (std::size_t i = 0; i < materials.size(); ++i) {
        const Material& m = materials[i];
        if (!finite(m.baseColor) || !finite(m.emission) || !finite(m.specularColor) || !std::isfinite(m.metallic) ||
            !std::isfinite(m.roughness) || !std::isfinite(m.specular) || !std::isfinite(m.baseAlpha) ||
            !std::isfinite(m.alphaCutoff))
            err << "material " << i << " ('" << m.name << "'): non-finite value\n";
        if (m.baseColorTexture >= int(textures.size())) err << "material " << i << ": texture index out of range\n";
    }
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        if (!finite(l.position) || !finite(l.direction) || !finite(l.intensity))
            err << "light " << i << " ('" << l.name << "'): non-finite value\n";
        // Refused, not clamped: the rasteriser would show black where the path tracer adds negative light.
        if (l.intensity.x < 0.0f || l.intensity.y < 0.0f || l.intensity.z < 0.0f)
            err << "light " << i << " ('" << l.name << "'): negative intensity\n";
        // glTF's cone: angles in [0, pi/2] (inner >= outer is the model's hard cone, Light::spotWeight).
        const float quarter = 0.5f * kPi * (1.0f + 1e-6f);
        if (l.type == LightType::Spot && !(l.innerConeRad >= 0.0f && l.outerConeRad > 0.0f &&
                                           l.outerConeRad <= quarter && l.innerConeRad <= quarter))
            err << "light " << i << " ('" << l.name << "'): spot cone angles outside [0, pi/2]\n";
    }
    if (!finite(camera.position) || !finite(camera.forward) || !finite(camera.up) || !std::isfinite(camera.yfovRad))
        err << "camera: non-finite value\n";
    if (!(camera.yfovRad > 0.0f && camera.yfovRad < kPi)) err << "camera: vertical field of view outside (0, pi)\n";
    if (!(camera.znear > 0.0f && camera.zfar > camera.znear)) err << "camera: needs 0 < znear < zfar\n";
    return err.str();
}

} // namespace bounce::core
