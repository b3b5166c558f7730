// core::Scene on the GPU: one vertex/index buffer for all meshes (world space), materials, lights and
// area-light polygons in SSBOs (layouts in glsl/common/scene.glsl), base-colour textures (with the alpha
// of masked materials) in one array, and for a scene with normal maps (core::Scene::hasNormalMaps) the
// normal textures in another and the vertices' tangents in a second vertex buffer.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "gl/resource/buffer.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"

namespace bounce::gl {

// std430 mirrors of glsl/common/scene.glsl.
struct GpuMaterial {
    glm::vec4 baseColorMetallic;
    glm::vec4 emissionRoughness;
    glm::vec4 specularColorSpecular;
    glm::ivec4 flags;
    glm::ivec4 normalMap{-1, 0, 0, 0}; // x: layer of normalTextures() or -1, y: the scale's float bits
};
// The lights' records on the GPU are the frame's: gl/frame/frame_lights.h.
inline constexpr int kLightPoint = 0, kLightSpot = 1, kLightDirectional = 2, kLightArea = 3;

// The scene's geometry as any shader reads it (glsl/common/scene.glsl, SCENE_GEOMETRY): the vertex buffer
// the rasteriser draws from, read as std430 floats (9 per vertex), the index buffer (3 per triangle), and
// the emissive triangles. Triangle t is the t-th triangle of the meshes in order, the order core::Scene,
// the BVH and the path tracer use.
struct GpuVertex {
    glm::vec3 position; // world space, metres
    glm::vec3 normal;
    glm::vec2 uv;
    std::uint32_t material;
};
static_assert(sizeof(GpuVertex) == 9 * sizeof(float), "scene.glsl reads 9 floats per vertex");
struct GpuEmissiveTriangle {
    std::uint32_t triangle;
    std::uint32_t material;
    float areaM2;
    float powerCdf; // the cumulative share of emitted power pi L A (luminance) up to and including this one
};
struct GpuEmissiveHeader {
    std::uint32_t count;
    float totalPowerW; // pi L A summed, luminance
    std::uint32_t pad[2];
};

// One light as the GPU sees it, before shadow layers are assigned.
struct LightSource {
    int type = kLightPoint;
    glm::vec3 position{0.0f};  // point/spot position; area: centroid of its emitting mesh
    glm::vec3 direction{0.0f}; // spot/directional travel direction; area: emitter normal
    glm::vec3 intensity{0.0f}; // W/sr, W/m^2, or radiance for area triangles
    float cosOuter = -1.0f, cosInner = -1.0f;
    float outerConeRad = 0.0f;
    glm::vec3 triangle[3]; // area only
    int group = -1;        // area triangles of one mesh share a shadow cube: the mesh index
};

// Whether one of `lights` is of kind `type` (kLight*): what the passes specialise their shaders on.
inline bool hasLightOfType(const std::vector<LightSource>& lights, int type)
{
    for (const LightSource& l : lights)
        if (l.type == type) return true;
    return false;
}

class GpuScene {
public:
    // Area triangles beyond this many are ignored with a warning (their emission is still seen).
    static constexpr int kMaxAreaTriangles = 256;

    GpuScene(const core::Scene& scene, int textureSize = 512);

    void draw() const; // binds the vertex array and draws every triangle
    // The meshes of masked materials, or the others, in as few index ranges as their order allows
    // (gl/frame/scene_program.h draws each with its shader variant).
    enum class Meshes { Opaque, Masked };
    void draw(Meshes which) const;
    // Binds vertices, indices and emissive triangles at SSBO_SCENE_* and the textures at UNIT_BASE_COLOR (gl/frame/bindings.h).
    void bindGeometry() const;
    int emissiveTriangleCount() const { return emissiveCount_; }
    void drawPositionsOnly() const { draw(); }
    // Every triangle with its neighbours (GL_TRIANGLES_ADJACENCY, core/adjacency.h: after each edge the far
    // corner of the triangle across it, or the triangle's own opposite corner at a boundary), positions only
    // (attribute 0). The adjacency is built from the vertex buffer at the first call: the topology, which
    // moveVertices does not change.
    void drawWithAdjacency() const;
    const Buffer& materials() const { return materials_; }
    const Texture& baseColorTextures() const { return textures_; }
    bool hasTextures() const { return hasTextures_; }
    // Normal maps (core::Scene::hasNormalMaps): the normal textures, linear RGBA8, one layer each, and the
    // tangents at vertex attribute 4 (glsl/frame/gbuffer.vert under NORMAL_MAPS; zero for the vertices of
    // meshes without tangents, which then keep their vertex normals). Without normal maps the array is one
    // texel and attribute 4 is off.
    bool hasNormalMaps() const { return hasNormalMaps_; }
    const Texture& normalTextures() const { return normalTextures_; }
    // Alpha-masked materials (glTF MASK): the passes that rasterise the scene compile their ALPHA_MASK
    // variant (glsl/common/base_color.glsl) only for such scenes, so other scenes pay no texture fetch
    // and no discard. Those variants read materials (SSBO_MATERIALS) and textures (UNIT_BASE_COLOR).
    bool hasAlphaMask() const { return hasAlphaMask_; }
    std::vector<Define> alphaMaskDefines() const;
    std::size_t triangleCount() const { return indexCount_ / 3; }
    std::size_t vertexCount() const { return vertices_.bytes() / sizeof(Vertex); }
    const core::Bounds& bounds() const { return bounds_; }
    // Deforming geometry: new positions and normals for every vertex (vertexCount() each, the order of the
    // meshes), rewritten in the buffer that the rasteriser and SCENE_GEOMETRY read; the area lights and the
    // emissive triangles follow (one that becomes degenerate emits nothing). Returns false, changing nothing,
    // where a count differs or a value is not finite. What was built from core::Scene on the CPU (BVHs) stays
    // where it was: see Frame::moveVertices.
    bool moveVertices(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals);

    // Lights of the scene: the punctual ones (from core::Light) first, then one per emissive triangle;
    // the demo may move punctual lights, which rebuilds this list through setLights().
    const std::vector<LightSource>& lights() const { return lights_; }
    int punctualLightCount() const { return int(punctual_.size()); } // lights() [0, this) are punctual
    void setLights(const std::vector<core::Light>& punctual);
    const std::vector<core::Light>& punctualLights() const { return punctual_; }

private:
    using Vertex = GpuVertex;
    VertexArray vao_;
    Buffer vertices_, indices_, materials_, emissive_;
    mutable VertexArray adjacencyVao_; // drawWithAdjacency's, made at its first call
    mutable Buffer adjacency_;
    int emissiveCount_ = 0;
    Buffer tangents_;
    std::vector<int> normalLayerOf_; // scene texture -> layer of normalTextures_, -1 when not a normal map
    void uploadNormalTextures(const core::Scene& scene);
    Texture textures_, normalTextures_;
    bool hasTextures_ = false;
    bool hasNormalMaps_ = false;
    bool hasAlphaMask_ = false;
    // Ranges of the index buffer for glMultiDrawElements.
    struct IndexRanges {
        std::vector<int> counts;
        std::vector<const void*> offsets; // bytes into the index buffer
        std::size_t end = 0;              // one past the last range's last index
        void add(std::size_t first, std::size_t count);
    };
    IndexRanges opaqueRanges_, maskedRanges_; // only for scenes with masks
    std::size_t indexCount_ = 0;
    core::Bounds bounds_;
    std::vector<core::Light> punctual_;
    // The emitting triangles (not degenerate when the scene was loaded), where placeEmitters() finds them.
    struct Emitter {
        std::uint32_t triangle = 0, material = 0;
        std::uint32_t corners[3] = {0, 0, 0}; // vertex indices
        glm::vec3 emission{0.0f};
        double luminance = 0.0;
        int group = -1;     // the mesh: its triangles share a shadow cube
        bool light = false; // one of the first kMaxAreaTriangles: an area light
    };
    std::vector<Emitter> emitters_;
    // area_ and the emissive triangles' buffer from the emitters' corners in `vertices`.
    void placeEmitters(const std::vector<Vertex>& vertices);
    std::vector<LightSource> area_;
    std::vector<LightSource> lights_;
};

} // namespace bounce::gl
