// core::Scene on Embree 3: one triangle geometry per mesh (geomID = mesh index), built once with high
// quality, queried with single rays (rtcIntersect1 / rtcOccluded1). Also the surface data the path
// tracer shades with: positions, normals, texture coordinates and decoded baseColor textures.
//
// Every triangle blocks rays from both sides (no back-face culling): one-sidedness is a shading rule
// (ref/README.md), never a visibility rule. Alpha-masked materials (glTF MASK) block rays only where
// their alpha reaches the cutoff: an Embree filter function on their meshes rejects hits in the holes,
// for closest hits, occlusion and allHits alike.
#pragma once

#include <cstdint>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "core/scene.h"
#include "core/texture_sampling.h"

namespace bounce::ref {

struct Hit {
    float t = 0.0f;
    std::uint32_t mesh = 0;   // Embree geomID
    std::uint32_t prim = 0;   // Embree primID: the triangle within the mesh
    float u = 0.0f, v = 0.0f; // p = (1 - u - v) p0 + u p1 + v p2
};

// A point on a surface as the integrator shades it.
struct SurfacePoint {
    glm::vec3 p{0.0f};
    glm::vec3 ng{0.0f, 0.0f, 1.0f}; // unit normal of the triangle as stored: its front (counter-clockwise) side
    glm::vec3 ns{0.0f, 0.0f, 1.0f}; // interpolated vertex normal, flipped onto ng's side when it is not, then
                                    // bent by the material's normal map (common/normal_map.glsl's formula)
    glm::vec2 uv{0.0f};
    std::uint32_t triangle = 0; // global triangle index (EmbreeScene::globalTriangle)
    const core::Material* material = nullptr;
};

class EmbreeScene {
public:
    // Throws std::invalid_argument when scene.validate() complains, std::runtime_error on Embree errors.
    // allHits() needs Embree's context filters enabled (withAllHits); they cost ordinary queries a little.
    explicit EmbreeScene(const core::Scene& scene, bool withAllHits = false);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Nearest hit with t in (tmin, tmax); rays counts the query.
    bool intersect(const glm::vec3& o, const glm::vec3& d, float tmin, float tmax, Hit& hit, std::uint64_t& rays) const;
    // Whether anything lies on the ray with t in (tmin, tmax).
    bool occluded(const glm::vec3& o, const glm::vec3& d, float tmin, float tmax, std::uint64_t& rays) const;
    // Every triangle the ray crosses with t in (tmin, tmax), each once, in no particular order (an
    // Embree context filter that records and rejects each candidate hit). Needs withAllHits.
    void allHits(const glm::vec3& o, const glm::vec3& d, float tmin, float tmax, std::vector<Hit>& out,
                 std::uint64_t& rays) const;

    SurfacePoint surface(const Hit& hit) const;
    std::uint32_t globalTriangle(std::uint32_t mesh, std::uint32_t prim) const { return triangleOffset_[mesh] + prim; }
    std::size_t triangleCount() const { return triangleOffset_.back(); }
    // The triangle's vertices by global index.
    void triangle(std::uint32_t global, glm::vec3& p0, glm::vec3& p1, glm::vec3& p2, std::uint32_t& mesh) const;
    // The material's baseColor texture at uv (bilinear, sRGB decoded, repeat wrap); 1 without a texture.
    glm::vec3 textureColor(const core::Material& m, const glm::vec2& uv) const;
    // The alpha of the material's baseColor texture at uv (bilinear, repeat wrap); 1 without a texture.
    // Kept for the textures of masked materials only.
    float textureAlpha(const core::Material& m, const glm::vec2& uv) const;
    // Whether (u, v) on the triangle lies in a hole of its alpha-masked material (core::Material::cutsOut).
    bool cutOut(std::uint32_t mesh, std::uint32_t prim, float u, float v) const;

    // How far to move a ray origin off a surface at p so the ray cannot hit that surface again: scaled
    // with the coordinates, where float spacing grows (1e-5 relative, 10 micrometres at 1 m).
    static float offsetScale(const glm::vec3& p);
    static glm::vec3 offsetOrigin(const glm::vec3& p, const glm::vec3& sideNormal)
    {
        return p + offsetScale(p) * sideNormal;
    }

    const core::Scene& scene() const { return scene_; }

private:
    struct LinearTexture {
        int width = 0, height = 0;
        std::vector<glm::vec3> texels; // linear RGB
    };
    // The tangents of a triangle's corners (core::Mesh::tangents), for its material's normal map.
    struct TangentRecord {
        glm::vec4 t0{0.0f}, t1{0.0f}, t2{0.0f};
    };
    // n bent by material m's normal map at uv with the interpolated tangent (n where nothing bends it).
    glm::vec3 normalMapped(const glm::vec3& n, const glm::vec4& tangent, const core::Material& m,
                           const glm::vec2& uv) const;

    const core::Scene& scene_;
    RTCDevice device_ = nullptr;
    RTCScene rtcScene_ = nullptr;
    // What shading needs of one triangle, gathered once so that a hit touches one cache line or two
    // instead of the mesh's index, position, normal and uv arrays.
    struct TriangleRecord {
        glm::vec3 p0, p1, p2;
        glm::vec3 ng;         // unit, front side
        glm::vec3 n0, n1, n2; // vertex normals
        glm::vec2 uv0, uv1, uv2;
        std::uint32_t mesh;
    };

    std::vector<std::uint32_t> triangleOffset_; // per mesh, plus the total at the end
    std::vector<TriangleRecord> triangles_;     // by global triangle index
    std::vector<LinearTexture> textures_;
    // With normal maps only (core::Scene::hasNormalMaps): by global triangle, zero for meshes without
    // tangents; and by scene texture, the normal maps' texels as they are stored (linear, 0..1).
    std::vector<TangentRecord> tangents_;
    std::vector<LinearTexture> normalTextures_;
    core::AlphaMasks masks_;
    bool withAllHits_ = false;
};

} // namespace bounce::ref
