#include "core/scene.h"

#include <algorithm>
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

bool Scene::hasNormalMaps() const
{
    for (const Mesh& m : meshes)
        if (m.material < materials.size() && materials[m.material].hasNormalMap() && !m.tangents.empty() &&
            !m.uvs.empty())
            return true;
    return false;
}

void dropNormalMaps(Scene& scene)
{
    for (Material& m : scene.materials) m.normalTexture = -1;
}

std::vector<glm::vec4> tangentsFromUvs(const Mesh& mesh)
{
    const std::size_t n = mesh.positions.size();
    std::vector<glm::dvec3> du(n, glm::dvec3(0.0)), dv(n, glm::dvec3(0.0));
    if (mesh.uvs.size() == n)
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            const std::uint32_t i[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
            if (i[0] >= n || i[1] >= n || i[2] >= n) continue;
            const glm::dvec3 e1 = glm::dvec3(mesh.positions[i[1]]) - glm::dvec3(mesh.positions[i[0]]);
            const glm::dvec3 e2 = glm::dvec3(mesh.positions[i[2]]) - glm::dvec3(mesh.positions[i[0]]);
            const glm::dvec2 w1 = glm::dvec2(mesh.uvs[i[1]]) - glm::dvec2(mesh.uvs[i[0]]);
            const glm::dvec2 w2 = glm::dvec2(mesh.uvs[i[2]]) - glm::dvec2(mesh.uvs[i[0]]);
            const double det = w1.x * w2.y - w2.x * w1.y;
            if (!(std::abs(det) > 1e-20) || !std::isfinite(det)) continue; // no uv area: no direction
            const glm::dvec3 sdir = (e1 * w2.y - e2 * w1.y) / det, tdir = (e2 * w1.x - e1 * w2.x) / det;
            if (!std::isfinite(glm::dot(sdir, sdir)) || !std::isfinite(glm::dot(tdir, tdir))) continue;
            for (std::uint32_t v : i) {
                du[v] += sdir;
                dv[v] += tdir;
            }
        }
    std::vector<glm::vec4> tangents(n);
    for (std::size_t v = 0; v < n; ++v) {
        const glm::dvec3 normal = v < mesh.normals.size() ? glm::dvec3(mesh.normals[v]) : glm::dvec3(0, 0, 1);
        glm::dvec3 t = du[v] - normal * glm::dot(normal, du[v]);
        double len = glm::length(t);
        if (!(len > 1e-12 * std::max(glm::length(du[v]), 1e-30)) || !std::isfinite(len)) {
            // Any direction in the tangent plane: the axis least aligned with the normal, made orthogonal.
            const glm::dvec3 a = std::abs(normal.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
            t = a - normal * glm::dot(normal, a);
            len = glm::length(t);
        }
        t /= len;
        const double handedness = glm::dot(glm::cross(normal, t), -dv[v]) < 0.0 ? -1.0 : 1.0;
        tangents[v] = glm::vec4(glm::vec3(t), float(handedness));
    }
    return tangents;
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
        // Hashed only where present, so that the keys of scenes without normal maps stay what they were.
        if (!m.tangents.empty()) addVector(f, m.tangents);
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
        if (m.hasNormalMap()) {
            f.addBytesOf(m.normalTexture);
            f.addBytesOf(m.normalScale);
        }
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
        if (!m.tangents.empty() && m.tangents.size() != m.positions.size())
            err << where << ": " << m.tangents.size() << " tangents for " << m.positions.size() << " positions\n";
        for (const glm::vec4& t : m.tangents)
            if (!finite(glm::vec3(t)) || !(t.w == 1.0f || t.w == -1.0f)) {
                err << where << ": tangent not finite or its handedness not +-1\n";
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
        if (m.normalTexture >= int(textures.size())) err << "material " << i << ": normal texture index out of range\n";
        if (!std::isfinite(m.normalScale))
            err << "material " << i << " ('" << m.name << "'): non-finite normal scale\n";
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
