#include "core/scene.h"

#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "core/hash.h"

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
// A vector's length, then its elements' bytes.
template <class T>
void addVector(Fnv1a& f, const std::vector<T>& v)
{
    f.addBytesOf(v.size());
    f.add(v.data(), v.size() * sizeof(T));
}

bool finite(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
} // namespace

std::uint64_t Scene::contentHash() const
{
    Fnv1a f(Fnv1a::kLegacyBasis); // the cache keys on disk were made with it (core/hash.h)
    f.addBytesOf(meshes.size());
    for (const Mesh& m : meshes) {
        addVector(f, m.positions);
        addVector(f, m.normals);
        addVector(f, m.uvs);
        addVector(f, m.indices);
        f.addBytesOf(m.material);
    }
    f.addBytesOf(materials.size());
    for (const Material& m : materials) {
        f.addBytesOf(m.baseColor);
        f.addBytesOf(m.baseColorTexture);
        f.addBytesOf(m.metallic);
        f.addBytesOf(m.roughness);
        f.addBytesOf(m.specular);
        f.addBytesOf(m.specularColor);
        f.addBytesOf(m.emission);
        f.addBytesOf(m.doubleSided);
        f.addBytesOf(m.alphaMode);
        f.addBytesOf(m.baseAlpha);
        f.addBytesOf(m.alphaCutoff);
    }
    f.addBytesOf(textures.size());
    for (const Texture& t : textures) {
        f.addBytesOf(t.width);
        f.addBytesOf(t.height);
        addVector(f, t.rgba8);
    }
    f.addBytesOf(lights.size());
    for (const Light& l : lights) {
        f.addBytesOf(l.type);
        f.addBytesOf(l.position);
        f.addBytesOf(l.direction);
        f.addBytesOf(l.intensity);
        f.addBytesOf(l.innerConeRad);
        f.addBytesOf(l.outerConeRad);
    }
    return f.value();
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
