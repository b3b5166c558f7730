// The scene model every part of Bounce shares: the real-time renderer (gl/), the ground truth (ref/)
// and the tools (app/) all read this one description. Units as in DESIGN.md: metres, radiance in
// W/(m^2 sr), punctual intensity in W/sr, directional irradiance in W/m^2, linear RGB.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::core {

inline constexpr float kPi = 3.14159265358979323846f;

// glTF's alphaMode: OPAQUE, or MASK (the surface exists where its alpha reaches alphaCutoff: leaves,
// fences, chains). BLEND (translucency) has no model here; the reader takes it as OPAQUE with a warning.
enum class AlphaMode { Opaque, Mask };

// One material, one BRDF (brdf.h): Lambertian diffuse baseColor x (1 - metallic) plus one GGX lobe.
struct Material {
    std::string name;
    glm::vec3 baseColor{1.0f}; // linear RGB; multiplied by the texture when there is one
    int baseColorTexture = -1; // index into Scene::textures, -1 when none
    float metallic = 0.0f;
    float roughness = 1.0f;        // GGX alpha = roughness^2
    float specular = 1.0f;         // KHR_materials_specular specularFactor; 0 gives pure Lambertian
    glm::vec3 specularColor{1.0f}; // KHR_materials_specular specularColorFactor
    glm::vec3 emission{0.0f};      // W/(m^2 sr): emissiveFactor x KHR_materials_emissive_strength
    bool doubleSided = false;      // shading only; every surface blocks light from both sides
    AlphaMode alphaMode = AlphaMode::Opaque;
    float baseAlpha = 1.0f;   // baseColorFactor's alpha, multiplied by the texture's alpha
    float alphaCutoff = 0.5f; // MASK: alpha below this is a hole, in every pass and in the path tracer
    // glTF's normalTexture: tangent-space normals (x right, y up in the image, z out of the surface, texels
    // linear, 2 v - 1), whose x and y are multiplied by normalScale. It bends the shading normal of the
    // meshes that carry tangents (Mesh::tangents), in the G-buffer and in the path tracer alike.
    int normalTexture = -1; // index into Scene::textures, -1 when none
    float normalScale = 1.0f;

    bool isEmissive() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }
    // True when the GGX lobe contributes (a Lambertian-only scene needs no glossy resources).
    bool isGlossy() const { return metallic > 0.0f || specular > 0.0f; }
    bool isMasked() const { return alphaMode == AlphaMode::Mask; }
    // glTF 3.9.4: a masked surface is "fully transparent" where baseColorFactor.a x texture alpha <
    // alphaCutoff, opaque elsewhere. textureAlpha is 1 without a texture.
    bool cutsOut(float textureAlpha) const { return isMasked() && baseAlpha * textureAlpha < alphaCutoff; }
    bool hasNormalMap() const { return normalTexture >= 0; }
};

// An 8-bit RGBA image, row 0 at the top (glTF image convention). As a base colour its colour is
// sRGB-encoded and its alpha linear (the mask of MASK materials); as a normal map every channel is linear.
struct Texture {
    std::string name;
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba8;
};

// A triangle mesh in world space: node transforms are applied when the scene is built or loaded.
struct Mesh {
    std::string name;
    std::vector<glm::vec3> positions; // metres
    std::vector<glm::vec3> normals;   // unit length, one per position
    std::vector<glm::vec2> uvs;       // one per position, or empty
    // glTF's TANGENT: one per position, or empty. xyz a unit tangent along +u, w = +-1 the handedness: the
    // bitangent (the normal map's +y) is w cross(normal, tangent). Read only through a normal map.
    std::vector<glm::vec4> tangents;
    std::vector<std::uint32_t> indices; // triangle list, counter-clockwise front faces
    std::uint32_t material = 0;         // index into Scene::materials
};

enum class LightType { Point, Spot, Directional };

// KHR_lights_punctual, with intensity read as W/sr (W/m^2 for directional), colour folded in.
struct Light {
    std::string name;
    LightType type = LightType::Point;
    glm::vec3 position{0.0f};               // point, spot
    glm::vec3 direction{0.0f, -1.0f, 0.0f}; // spot, directional: the direction light travels (unit)
    glm::vec3 intensity{1.0f};              // colour x intensity
    float innerConeRad = 0.0f;              // spot: full intensity inside
    float outerConeRad = kPi / 4.0f;        // spot: nothing outside; inner == outer is a hard edge

    // Angular falloff of a spot (glTF's: t = (cos - cosOuter) / (cosInner - cosOuter), weight t^2),
    // 1 for point and directional lights. A hard cone (inner >= outer) is a step at the outer angle.
    float spotWeight(float cosAngle) const;
};

// A pinhole camera. The aspect ratio comes from the image, the vertical field of view from here.
struct Camera {
    glm::vec3 position{0.0f};
    glm::vec3 forward{0.0f, 0.0f, 1.0f}; // unit
    glm::vec3 up{0.0f, 1.0f, 0.0f};      // unit, orthogonal to forward
    float yfovRad = 0.6860514f;          // the canonical 2 atan(12.5/35)
    float znear = 0.01f;
    float zfar = 100.0f;

    glm::mat4 view() const;                   // world to eye (OpenGL: eye looks down -z)
    glm::mat4 projection(float aspect) const; // eye to clip (OpenGL, depth -1..1)
    // The world-space direction through pixel centre (px, py) of a width x height image, row 0 top.
    glm::vec3 rayDirection(float px, float py, int width, int height) const;
};

struct Bounds {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};
    void extend(const glm::vec3& p)
    {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
    glm::vec3 extent() const { return empty() ? glm::vec3(0.0f) : hi - lo; }
    glm::vec3 centre() const { return empty() ? glm::vec3(0.0f) : 0.5f * (lo + hi); }
};

struct Scene {
    std::string name;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Light> lights;
    Camera camera;
    // Where the camera came from, for logs and run records: "built-in", "glTF", "framed the bounds (the
    // glTF has no camera)", "setup", "command line".
    std::string cameraSource = "built-in";

    Bounds bounds() const;
    std::size_t triangleCount() const;
    bool hasEmission() const;
    bool hasGlossy() const;
    bool hasAlphaMask() const; // some mesh's material is alpha-masked
    // Some mesh with uvs and tangents has a material with a normal texture: what the renderers bend
    // normals on (a mesh without tangents shades with its vertex normals).
    bool hasNormalMaps() const;
    // FNV-1a over geometry, materials, textures and lights (not the camera, not names): the key of
    // cached references together with camera, size and light paths.
    std::uint64_t contentHash() const;
    // Empty when valid, else what is wrong (indices out of range, NaN/Inf, unit vectors...).
    std::string validate() const;
    // Moves every vertex, in place: positions[v] and normals[v] for the meshes' vertices in order (mesh by
    // mesh, as the GPU scene lays them out); the moved scene as a loader would give it. Throws
    // std::out_of_range, changing nothing, where the counts differ.
    // Tangents stay as they were: the renderers orthogonalise them against the moved normals.
    void setVertices(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals);
};

// The scene as it shades without normal maps (every material's normalTexture -1; the textures stay):
// `bounce reference --no-normal-maps`, the path tracer's side of the frame parameter normalMaps=0. Its
// contentHash differs from the scene's where the scene had a normal map, so cached references of the two
// never mix.
void dropNormalMaps(Scene& scene);

// Tangents for a mesh with uvs and normals whose file has none: at each vertex the sum over its triangles
// of dP/du and of dP/dv (Lengyel's), the first made orthogonal to the vertex normal and unit, the
// handedness w chosen so that w cross(normal, tangent) points along -dP/dv, the image's +y (glTF's v grows
// down the image; this is MikkTSpace's convention with v flipped, which the files' own tangents follow).
// Not MikkTSpace itself: no splitting at uv seams. A vertex whose triangles span no uv area gets any unit
// tangent orthogonal to its normal.
std::vector<glm::vec4> tangentsFromUvs(const Mesh& mesh);

} // namespace bounce::core
