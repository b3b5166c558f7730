#include "core/cornell.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <functional>

#include "core/gltf_io.h"
#include "core/scene_setup.h"

namespace bounce::core {

namespace {

using Quad = std::array<glm::vec3, 4>;

// Every number below is cornell-box.md's, in metres. Keep them exact: other renderers are compared
// against the project on this geometry.
const Quad kFloor{{{0.5528f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.5592f}, {0.5496f, 0.0f, 0.5592f}}};
const Quad kCeiling{
    {{0.556f, 0.5488f, 0.0f}, {0.556f, 0.5488f, 0.5592f}, {0.0f, 0.5488f, 0.5592f}, {0.0f, 0.5488f, 0.0f}}};
const Quad kBackWall{
    {{0.5496f, 0.0f, 0.5592f}, {0.0f, 0.0f, 0.5592f}, {0.0f, 0.5488f, 0.5592f}, {0.556f, 0.5488f, 0.5592f}}};
const Quad kRightWall{{{0.0f, 0.0f, 0.5592f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.5488f, 0.0f}, {0.0f, 0.5488f, 0.5592f}}};
const Quad kLeftWall{
    {{0.5528f, 0.0f, 0.0f}, {0.5496f, 0.0f, 0.5592f}, {0.556f, 0.5488f, 0.5592f}, {0.556f, 0.5488f, 0.0f}}};

const std::array<Quad, 5> kShortBlock{{
    {{{0.130f, 0.165f, 0.065f}, {0.082f, 0.165f, 0.225f}, {0.240f, 0.165f, 0.272f}, {0.290f, 0.165f, 0.114f}}},
    {{{0.290f, 0.0f, 0.114f}, {0.290f, 0.165f, 0.114f}, {0.240f, 0.165f, 0.272f}, {0.240f, 0.0f, 0.272f}}},
    {{{0.130f, 0.0f, 0.065f}, {0.130f, 0.165f, 0.065f}, {0.290f, 0.165f, 0.114f}, {0.290f, 0.0f, 0.114f}}},
    {{{0.082f, 0.0f, 0.225f}, {0.082f, 0.165f, 0.225f}, {0.130f, 0.165f, 0.065f}, {0.130f, 0.0f, 0.065f}}},
    {{{0.240f, 0.0f, 0.272f}, {0.240f, 0.165f, 0.272f}, {0.082f, 0.165f, 0.225f}, {0.082f, 0.0f, 0.225f}}},
}};
const std::array<Quad, 5> kTallBlock{{
    {{{0.423f, 0.330f, 0.247f}, {0.265f, 0.330f, 0.296f}, {0.314f, 0.330f, 0.456f}, {0.472f, 0.330f, 0.406f}}},
    {{{0.423f, 0.0f, 0.247f}, {0.423f, 0.330f, 0.247f}, {0.472f, 0.330f, 0.406f}, {0.472f, 0.0f, 0.406f}}},
    {{{0.472f, 0.0f, 0.406f}, {0.472f, 0.330f, 0.406f}, {0.314f, 0.330f, 0.456f}, {0.314f, 0.0f, 0.456f}}},
    {{{0.314f, 0.0f, 0.456f}, {0.314f, 0.330f, 0.456f}, {0.265f, 0.330f, 0.296f}, {0.265f, 0.0f, 0.296f}}},
    {{{0.265f, 0.0f, 0.296f}, {0.265f, 0.330f, 0.296f}, {0.423f, 0.330f, 0.247f}, {0.423f, 0.0f, 0.247f}}},
}};
const Quad kLightQuad{
    {{0.343f, 0.5487f, 0.227f}, {0.343f, 0.5487f, 0.332f}, {0.213f, 0.5487f, 0.332f}, {0.213f, 0.5487f, 0.227f}}};

const glm::vec3 kWhite{0.725f, 0.71f, 0.68f};
const glm::vec3 kRed{0.63f, 0.065f, 0.05f};
const glm::vec3 kGreen{0.14f, 0.45f, 0.091f};
const glm::vec3 kAreaRadiance{17.0f, 12.0f, 4.0f};          // W/(m^2 sr)
const glm::vec3 kSpotIntensity{0.23205f, 0.1638f, 0.0546f}; // W/sr: the radiance times the quad's 0.01365 m^2
const glm::vec3 kSpotPosition{0.278f, 0.5478f, 0.2795f};
const glm::vec3 kPointPosition{0.278f, 0.40f, 0.2795f};

Material lambertian(const std::string& name, const glm::vec3& albedo)
{
    Material m;
    m.name = name;
    m.baseColor = albedo;
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    m.specular = 0.0f; // no glossy lobe: pure Lambertian
    return m;
}

// cornell-glossy's tall block: a rough white metal (cornell-box.md). baseColor 1 and metallic 1 give
// F0 = 1, so the Fresnel term is 1 at every angle and f = D Vis with GGX alpha = 0.3^2.
Material roughWhiteMetal()
{
    Material m;
    m.name = "rough white metal";
    m.baseColor = glm::vec3(1.0f);
    m.metallic = 1.0f;
    m.roughness = 0.3f;
    return m;
}

// cornell-mirror's tall block: the same metal polished (cornell-box.md), GGX alpha = 0.05^2.
Material polishedWhiteMetal()
{
    Material m = roughWhiteMetal();
    m.name = "polished white metal";
    m.roughness = 0.05f;
    return m;
}

// cornell-panels (the project's own, not in cornell-box.md): cornell-area's light split into four panels
// of half its width and depth, one over each quarter of the ceiling, at its height and radiance, so the
// four emit the same power as the one. Light independence (issue 27): ray bundles cost the same per
// direction for one panel or four, where the frame's direct light pays per light.
std::vector<Quad> ceilingPanels()
{
    const float hx = 0.25f * (kLightQuad[0].x - kLightQuad[2].x), hz = 0.25f * (kLightQuad[1].z - kLightQuad[0].z);
    const float y = kLightQuad[0].y;
    std::vector<Quad> panels;
    for (float cz : {0.1395f, 0.4195f})
        for (float cx : {0.138f, 0.418f})
            panels.push_back(
                {{{cx + hx, y, cz - hz}, {cx + hx, y, cz + hz}, {cx - hx, y, cz + hz}, {cx - hx, y, cz - hz}}});
    return panels;
}

// Which way a triangle's normal must point, given the triangle's centroid.
using Facing = std::function<glm::dvec3(const glm::dvec3& centroid)>;

// Splits each quad into (v0,v1,v2), (v0,v2,v3) as the scene description prescribes. Each triangle gets
// its own three vertices and its own geometric normal: the red wall is not planar, so one normal per
// quad would be wrong for one of its halves. Where the listed order winds the wrong way, the triangle
// is flipped (same three corners) so that it is counter-clockwise seen from the side its normal faces.
Mesh quadMesh(const std::string& name, std::uint32_t material, const std::vector<Quad>& quads, const Facing& facing)
{
    Mesh mesh;
    mesh.name = name;
    mesh.material = material;
    for (const Quad& q : quads) {
        for (const std::array<glm::vec3, 3>& tri : {std::array{q[0], q[1], q[2]}, std::array{q[0], q[2], q[3]}}) {
            const glm::dvec3 a(tri[0]), b(tri[1]), c(tri[2]);
            glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
            const bool flip = glm::dot(n, facing((a + b + c) / 3.0)) < 0.0;
            if (flip) n = -n;
            const std::uint32_t base = std::uint32_t(mesh.positions.size());
            mesh.positions.push_back(tri[0]);
            mesh.positions.push_back(flip ? tri[2] : tri[1]);
            mesh.positions.push_back(flip ? tri[1] : tri[2]);
            // + 0: no negative zeros in the stored normals (they would print as -0.0 in glTF files).
            const glm::vec3 normal = glm::vec3(n) + glm::vec3(0.0f);
            for (int k = 0; k < 3; ++k) {
                mesh.normals.push_back(normal);
                mesh.indices.push_back(base + std::uint32_t(k));
            }
        }
    }
    return mesh;
}

Facing towards(const glm::dvec3& point)
{
    return [point](const glm::dvec3& centroid) { return point - centroid; };
}

Facing awayFrom(const glm::dvec3& point)
{
    return [point](const glm::dvec3& centroid) { return centroid - point; };
}

glm::dvec3 centreOf(const std::array<Quad, 5>& block)
{
    glm::dvec3 sum(0.0);
    for (const Quad& q : block)
        for (const glm::vec3& v : q) sum += glm::dvec3(v);
    return sum / 20.0;
}

Light punctual(const std::string& name, LightType type, const glm::vec3& position)
{
    Light l;
    l.name = name;
    l.type = type;
    l.position = position;
    l.intensity = kSpotIntensity;
    if (type == LightType::Spot) {
        l.direction = glm::vec3(0.0f, -1.0f, 0.0f);
        l.innerConeRad = kPi / 4.0f; // inner == outer: the hard 45-degree cone of the scene description
        l.outerConeRad = kPi / 4.0f;
    }
    return l;
}

// An axis-aligned box as quads (each listed once; quadMesh orients them away from the box's centre).
std::vector<Quad> boxQuads(const glm::vec3& lo, const glm::vec3& hi, bool withBottom)
{
    const auto corner = [&](int i) { return glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z); };
    std::vector<Quad> q = {
        {corner(2), corner(3), corner(7), corner(6)}, // top
        {corner(0), corner(2), corner(6), corner(4)}, // -x
        {corner(1), corner(3), corner(7), corner(5)}, // +x
        {corner(0), corner(1), corner(3), corner(2)}, // -z
        {corner(4), corner(5), corner(7), corner(6)}, // +z
    };
    if (withBottom) q.push_back({corner(0), corner(1), corner(5), corner(4)});
    return q;
}

// cornell-slats: cornell-spot with more depth complexity, the project's own second scene for the image-
// space techniques (not part of cornell-box.md). Seven white slats 2.5 cm wide and 25 cm high stand in
// a row 2-3.5 cm behind the open front, so that the eye sees the blocks through gaps; a white shelf
// 1.5 cm thick spans from the green wall to x = 0.2 m at 0.36 m height, shading the floor below it and
// cutting the light's view of the green wall.
void addSlatsAndShelf(Scene& scene, std::uint32_t material)
{
    std::vector<Quad> slats;
    for (int k = 0; k < 7; ++k) {
        const float x = 0.07f + 0.07f * float(k);
        for (const Quad& q : boxQuads({x - 0.0125f, 0.0f, 0.02f}, {x + 0.0125f, 0.25f, 0.035f}, false))
            slats.push_back(q);
    }
    const auto centreOfAll = [](const std::vector<Quad>& quads) {
        glm::dvec3 c(0.0);
        for (const Quad& q : quads)
            for (const glm::vec3& v : q) c += glm::dvec3(v);
        return c / double(4 * quads.size());
    };
    // Each slat faces away from its own axis: the facing of a face is taken from its centroid's x.
    scene.meshes.push_back(quadMesh("slats", material, slats, [](const glm::dvec3& c) {
        const double k = std::round((c.x - 0.07) / 0.07), x = 0.07 + 0.07 * k;
        return c - glm::dvec3(x, 0.125, 0.0275);
    }));
    const std::vector<Quad> shelf = boxQuads({0.0f, 0.36f, 0.15f}, {0.2f, 0.375f, 0.45f}, true);
    scene.meshes.push_back(quadMesh("shelf", material, shelf, awayFrom(centreOfAll(shelf))));
}

} // namespace

std::vector<std::string> builtinSceneNames()
{
    return {"cornell-area",  "cornell-spot",   "cornell-point",  "cornell-point-ceiling",
            "cornell-slats", "cornell-glossy", "cornell-mirror", "cornell-panels"};
}

Scene makeCornell(std::string_view variant)
{
    const std::vector<std::string> names = builtinSceneNames();
    if (std::find(names.begin(), names.end(), variant) == names.end())
        throw SceneError(std::string(variant) + ": not a Cornell box variant (cornell-area, cornell-spot, "
                                                "cornell-point, cornell-point-ceiling, cornell-slats, "
                                                "cornell-glossy, cornell-mirror, cornell-panels)");

    Scene scene;
    scene.name = std::string(variant);
    scene.materials = {lambertian("white", kWhite), lambertian("red", kRed), lambertian("green", kGreen)};
    const std::uint32_t white = 0, red = 1, green = 2;

    const Facing intoRoom = towards(glm::dvec3(0.278, 0.2744, 0.2796)); // the middle of the room
    scene.meshes.push_back(quadMesh("floor", white, {kFloor}, intoRoom));
    scene.meshes.push_back(quadMesh("ceiling", white, {kCeiling}, intoRoom));
    scene.meshes.push_back(quadMesh("back wall", white, {kBackWall}, intoRoom));
    scene.meshes.push_back(quadMesh("right wall", green, {kRightWall}, intoRoom));
    scene.meshes.push_back(quadMesh("left wall", red, {kLeftWall}, intoRoom));
    scene.meshes.push_back(
        quadMesh("short block", white, {kShortBlock.begin(), kShortBlock.end()}, awayFrom(centreOf(kShortBlock))));
    std::uint32_t tallBlock = white;
    if (variant == "cornell-glossy" || variant == "cornell-mirror") {
        scene.materials.push_back(variant == "cornell-glossy" ? roughWhiteMetal() : polishedWhiteMetal());
        tallBlock = std::uint32_t(scene.materials.size() - 1);
    }
    scene.meshes.push_back(
        quadMesh("tall block", tallBlock, {kTallBlock.begin(), kTallBlock.end()}, awayFrom(centreOf(kTallBlock))));

    if (variant == "cornell-area" || variant == "cornell-glossy" || variant == "cornell-mirror" ||
        variant == "cornell-panels") {
        // Emits from its front face (down) only and reflects nothing.
        Material emitter = lambertian("light", glm::vec3(0.0f));
        emitter.emission = kAreaRadiance;
        scene.materials.push_back(emitter);
        const auto down = [](const glm::dvec3&) { return glm::dvec3(0.0, -1.0, 0.0); };
        const std::uint32_t light = std::uint32_t(scene.materials.size() - 1);
        if (variant == "cornell-panels") {
            const std::vector<Quad> panels = ceilingPanels();
            for (std::size_t k = 0; k < panels.size(); ++k)
                scene.meshes.push_back(quadMesh("light " + std::to_string(k + 1), light, {panels[k]}, down));
        } else {
            scene.meshes.push_back(quadMesh("light", light, {kLightQuad}, down));
        }
    } else if (variant == "cornell-spot" || variant == "cornell-slats") {
        scene.lights.push_back(punctual("spot", LightType::Spot, kSpotPosition));
        if (variant == "cornell-slats") addSlatsAndShelf(scene, white);
    } else if (variant == "cornell-point") {
        scene.lights.push_back(punctual("point", LightType::Point, kPointPosition));
    } else { // cornell-point-ceiling
        scene.lights.push_back(punctual("point", LightType::Point, kSpotPosition));
    }

    Camera& camera = scene.camera;
    camera.position = glm::vec3(0.278f, 0.273f, -0.800f);
    camera.forward = glm::vec3(0.0f, 0.0f, 1.0f);
    camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    camera.yfovRad = float(2.0 * std::atan(12.5 / 35.0)); // 35 mm lens on 25 mm film
    camera.znear = 0.01f;
    camera.zfar = 10.0f; // the room is 0.56 m deep, seen from 0.8 m in front of it
    return scene;
}

Scene loadScene(const std::string& nameOrPath)
{
    const std::vector<std::string> names = builtinSceneNames();
    if (std::find(names.begin(), names.end(), nameOrPath) != names.end()) return makeCornell(nameOrPath);
    std::string lower = nameOrPath;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    const auto endsWith = [&lower](const std::string& ext) {
        return lower.size() > ext.size() && lower.compare(lower.size() - ext.size(), ext.size(), ext) == 0;
    };
    if (endsWith(".gltf") || endsWith(".glb")) return loadGltf(nameOrPath);
    if (endsWith(".json")) return loadSetup(nameOrPath);
    std::string known;
    for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
    throw SceneError(nameOrPath + ": neither a built-in scene (" + known +
                     "), a .gltf/.glb file nor a scene setup (.json)");
}

} // namespace bounce::core
