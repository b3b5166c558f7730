// The generated Cornell box against shared/scenes/cornell-box.md: exact numbers, orientation of every
// triangle, materials, lights and camera.
#include "core/cornell.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/gltf_io.h"

namespace bounce::core {
namespace {

const glm::vec3 kRoomCentre{0.278f, 0.2744f, 0.2796f};

const Mesh& meshNamed(const Scene& s, const std::string& name)
{
    for (const Mesh& m : s.meshes)
        if (m.name == name) return m;
    throw std::runtime_error("no mesh " + name);
}

bool hasVertex(const Mesh& m, const glm::vec3& v)
{
    for (const glm::vec3& p : m.positions)
        if (p == v) return true; // exact: the scene description's numbers, not approximations
    return false;
}

glm::vec3 centroidOf(const Mesh& m)
{
    glm::dvec3 sum(0.0);
    for (const glm::vec3& p : m.positions) sum += glm::dvec3(p);
    return glm::vec3(sum / double(m.positions.size()));
}

// Calls f(a, b, c, n) for every triangle with its stored normal (flat: the same at its three corners).
template <class F>
void forEachTriangle(const Mesh& m, F f)
{
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
        const std::uint32_t i0 = m.indices[t], i1 = m.indices[t + 1], i2 = m.indices[t + 2];
        ASSERT_EQ(m.normals[i0], m.normals[i1]);
        ASSERT_EQ(m.normals[i0], m.normals[i2]);
        f(m.positions[i0], m.positions[i1], m.positions[i2], m.normals[i0]);
    }
}

TEST(Cornell, TriangleCounts)
{
    EXPECT_EQ(makeCornell("cornell-area").triangleCount(), 2u * (5 + 5 + 5) + 2);
    for (const char* v : {"cornell-spot", "cornell-point", "cornell-point-ceiling"})
        EXPECT_EQ(makeCornell(v).triangleCount(), 30u) << v;
    // Seven open-bottomed slats (5 quads) and a closed shelf (6 quads) on top of cornell-spot's 30.
    EXPECT_EQ(makeCornell("cornell-slats").triangleCount(), 30u + 2u * (7 * 5 + 6));
    EXPECT_EQ(makeCornell("cornell-glossy").triangleCount(), makeCornell("cornell-area").triangleCount());
}

// cornell-box.md's glossy variant: cornell-area with the tall block's five faces a rough white metal
// (baseColor 1, metallic 1, roughness 0.3), everything else unchanged.
TEST(Cornell, GlossyVariantIsTheAreaBoxWithAMetalTallBlock)
{
    const Scene glossy = makeCornell("cornell-glossy"), area = makeCornell("cornell-area");
    const Material& metal = glossy.materials[meshNamed(glossy, "tall block").material];
    EXPECT_EQ(metal.baseColor, glm::vec3(1.0f));
    EXPECT_EQ(metal.metallic, 1.0f);
    EXPECT_EQ(metal.roughness, 0.3f);
    EXPECT_TRUE(metal.isGlossy());
    for (const Mesh& m : glossy.meshes) {
        if (m.name == "tall block") continue;
        const Mesh& a = meshNamed(area, m.name);
        EXPECT_EQ(m.positions, a.positions) << m.name;
        EXPECT_EQ(glossy.materials[m.material].baseColor, area.materials[a.material].baseColor) << m.name;
        EXPECT_EQ(glossy.materials[m.material].emission, area.materials[a.material].emission) << m.name;
        EXPECT_FALSE(glossy.materials[m.material].isGlossy()) << m.name;
    }
}

TEST(Cornell, AllVariantsAreValid)
{
    for (const std::string& name : builtinSceneNames()) {
        const Scene s = makeCornell(name);
        EXPECT_EQ(s.validate(), "") << name;
        EXPECT_EQ(s.name, name);
    }
}

// cornell-panels: four separate emitting meshes whose area (so power, at one radiance) is the one light's;
// cornell-mirror: cornell-glossy's block polished to roughness 0.05.
TEST(Cornell, PanelsEmitTheOneLightsPowerAndTheMirrorIsPolished)
{
    const auto emittingArea = [](const Scene& s, int* meshes) {
        double a = 0.0;
        *meshes = 0;
        for (const Mesh& m : s.meshes) {
            if (s.materials[m.material].emission == glm::vec3(0.0f)) continue;
            ++*meshes;
            for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
                const glm::vec3 p0 = m.positions[m.indices[t]], p1 = m.positions[m.indices[t + 1]],
                                p2 = m.positions[m.indices[t + 2]];
                a += 0.5 * double(glm::length(glm::cross(p1 - p0, p2 - p0)));
            }
        }
        return a;
    };
    int one = 0, four = 0;
    const double a1 = emittingArea(makeCornell("cornell-area"), &one);
    const double a4 = emittingArea(makeCornell("cornell-panels"), &four);
    EXPECT_EQ(one, 1);
    EXPECT_EQ(four, 4);
    EXPECT_NEAR(a4, a1, 1e-6);
    const Scene mirror = makeCornell("cornell-mirror");
    EXPECT_FLOAT_EQ(mirror.materials[meshNamed(mirror, "tall block").material].roughness, 0.05f);
    EXPECT_FLOAT_EQ(mirror.materials[meshNamed(mirror, "tall block").material].metallic, 1.0f);
}

TEST(Cornell, VerticesAreThePublishedNumbers)
{
    const Scene s = makeCornell("cornell-area");
    EXPECT_TRUE(hasVertex(meshNamed(s, "floor"), {0.5528f, 0.0f, 0.0f}));
    EXPECT_TRUE(hasVertex(meshNamed(s, "floor"), {0.5496f, 0.0f, 0.5592f}));
    EXPECT_TRUE(hasVertex(meshNamed(s, "ceiling"), {0.556f, 0.5488f, 0.5592f}));
    EXPECT_TRUE(hasVertex(meshNamed(s, "back wall"), {0.0f, 0.5488f, 0.5592f}));
    EXPECT_TRUE(hasVertex(meshNamed(s, "right wall"), {0.0f, 0.5488f, 0.0f}));
    EXPECT_TRUE(hasVertex(meshNamed(s, "left wall"), {0.556f, 0.5488f, 0.0f}));
    EXPECT_TRUE(hasVertex(meshNamed(s, "short block"), {0.082f, 0.165f, 0.225f}));
    EXPECT_TRUE(hasVertex(meshNamed(s, "short block"), {0.240f, 0.0f, 0.272f}));
    EXPECT_TRUE(hasVertex(meshNamed(s, "tall block"), {0.265f, 0.330f, 0.296f}));
    EXPECT_TRUE(hasVertex(meshNamed(s, "tall block"), {0.472f, 0.0f, 0.406f}));
    EXPECT_TRUE(hasVertex(meshNamed(s, "light"), {0.343f, 0.5487f, 0.227f}));
    EXPECT_TRUE(hasVertex(meshNamed(s, "light"), {0.213f, 0.5487f, 0.332f}));
    const Bounds b = s.bounds();
    EXPECT_EQ(b.lo, glm::vec3(0.0f));
    EXPECT_EQ(b.hi, glm::vec3(0.556f, 0.5488f, 0.5592f));
}

TEST(Cornell, RedWallSplitFollowsTheDescription)
{
    // The red wall is not planar; the split (v0,v1,v2), (v0,v2,v3) decides its shape: both triangles
    // share the diagonal v0-v2 = (0.5528,0,0)-(0.556,0.5488,0.5592), so no triangle contains v1 and v3.
    const Scene s = makeCornell("cornell-spot");
    const Mesh& red = meshNamed(s, "left wall");
    const glm::vec3 v1{0.5496f, 0.0f, 0.5592f}, v3{0.556f, 0.5488f, 0.0f};
    forEachTriangle(red, [&](const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3&) {
        const bool hasV1 = a == v1 || b == v1 || c == v1;
        const bool hasV3 = a == v3 || b == v3 || c == v3;
        EXPECT_FALSE(hasV1 && hasV3);
    });
}

TEST(Cornell, NormalsAreUnitFlatAndMatchTheWinding)
{
    const Scene s = makeCornell("cornell-area");
    for (const Mesh& m : s.meshes) {
        ASSERT_EQ(m.normals.size(), m.positions.size());
        forEachTriangle(m, [&](const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& n) {
            EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f) << m.name;
            // Counter-clockwise seen from the side the normal points to.
            EXPECT_GT(glm::dot(glm::normalize(glm::cross(b - a, c - a)), n), 0.9999f) << m.name;
        });
    }
}

TEST(Cornell, WallsFaceIntoTheRoom)
{
    const Scene s = makeCornell("cornell-area");
    for (const char* wall : {"floor", "ceiling", "back wall", "right wall", "left wall"}) {
        forEachTriangle(meshNamed(s, wall),
                        [&](const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& n) {
                            EXPECT_GT(glm::dot(n, kRoomCentre - (a + b + c) / 3.0f), 0.0f) << wall;
                        });
    }
    EXPECT_EQ(meshNamed(s, "floor").normals[0], glm::vec3(0, 1, 0));
    EXPECT_EQ(meshNamed(s, "ceiling").normals[0], glm::vec3(0, -1, 0));
    EXPECT_EQ(meshNamed(s, "back wall").normals[0], glm::vec3(0, 0, -1));
    EXPECT_EQ(meshNamed(s, "right wall").normals[0], glm::vec3(1, 0, 0));
    EXPECT_LT(meshNamed(s, "left wall").normals[0].x, -0.99f);
}

TEST(Cornell, BlockFacesPointOutOfTheBlocks)
{
    const Scene s = makeCornell("cornell-spot");
    for (const char* block : {"short block", "tall block"}) {
        const Mesh& m = meshNamed(s, block);
        EXPECT_EQ(m.indices.size(), 5u * 2 * 3) << block;
        const glm::vec3 centre = centroidOf(m);
        int up = 0;
        forEachTriangle(m, [&](const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& n) {
            EXPECT_GT(glm::dot(n, (a + b + c) / 3.0f - centre), 0.0f) << block;
            if (n == glm::vec3(0, 1, 0))
                ++up;
            else
                EXPECT_NEAR(n.y, 0.0f, 1e-6f) << block << ": side faces are vertical";
        });
        EXPECT_EQ(up, 2) << block << ": the top quad faces up";
    }
}

TEST(Cornell, EmitterFacesDownAndReflectsNothing)
{
    const Scene s = makeCornell("cornell-area");
    const Mesh& light = meshNamed(s, "light");
    EXPECT_EQ(light.indices.size(), 6u);
    double area = 0.0;
    forEachTriangle(light, [&](const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& n) {
        EXPECT_EQ(n, glm::vec3(0, -1, 0));
        area += 0.5 * glm::length(glm::cross(glm::dvec3(b - a), glm::dvec3(c - a)));
    });
    EXPECT_NEAR(area, 0.01365, 1e-8);
    const Material& m = s.materials[light.material];
    EXPECT_EQ(m.emission, glm::vec3(17.0f, 12.0f, 4.0f));
    EXPECT_EQ(m.baseColor, glm::vec3(0.0f));
    EXPECT_EQ(m.specular, 0.0f);
    EXPECT_FALSE(m.doubleSided);
    EXPECT_TRUE(s.hasEmission());
    EXPECT_TRUE(s.lights.empty());
}

TEST(Cornell, MaterialsArePureLambertian)
{
    const Scene s = makeCornell("cornell-area");
    EXPECT_FALSE(s.hasGlossy());
    for (const Material& m : s.materials) {
        EXPECT_EQ(m.metallic, 0.0f) << m.name;
        EXPECT_EQ(m.specular, 0.0f) << m.name;
        EXPECT_EQ(m.roughness, 1.0f) << m.name;
        EXPECT_EQ(m.baseColorTexture, -1) << m.name;
    }
    EXPECT_EQ(s.materials[meshNamed(s, "floor").material].baseColor, glm::vec3(0.725f, 0.71f, 0.68f));
    EXPECT_EQ(s.materials[meshNamed(s, "left wall").material].baseColor, glm::vec3(0.63f, 0.065f, 0.05f));
    EXPECT_EQ(s.materials[meshNamed(s, "right wall").material].baseColor, glm::vec3(0.14f, 0.45f, 0.091f));
}

TEST(Cornell, PunctualLights)
{
    const Scene spot = makeCornell("cornell-spot");
    ASSERT_EQ(spot.lights.size(), 1u);
    const Light& l = spot.lights[0];
    EXPECT_EQ(l.type, LightType::Spot);
    EXPECT_EQ(l.position, glm::vec3(0.278f, 0.5478f, 0.2795f));
    EXPECT_EQ(l.direction, glm::vec3(0.0f, -1.0f, 0.0f));
    EXPECT_EQ(l.intensity, glm::vec3(0.23205f, 0.1638f, 0.0546f));
    EXPECT_EQ(l.innerConeRad, l.outerConeRad);
    EXPECT_NEAR(l.outerConeRad, kPi / 4.0f, 1e-7f);
    EXPECT_EQ(l.spotWeight(std::cos(0.78f)), 1.0f); // hard cone: full inside...
    EXPECT_EQ(l.spotWeight(std::cos(0.79f)), 0.0f); // ...nothing outside
    EXPECT_FALSE(spot.hasEmission());

    const Scene point = makeCornell("cornell-point");
    ASSERT_EQ(point.lights.size(), 1u);
    EXPECT_EQ(point.lights[0].type, LightType::Point);
    EXPECT_EQ(point.lights[0].position, glm::vec3(0.278f, 0.40f, 0.2795f));
    EXPECT_EQ(point.lights[0].intensity, l.intensity);

    const Scene ceiling = makeCornell("cornell-point-ceiling");
    ASSERT_EQ(ceiling.lights.size(), 1u);
    EXPECT_EQ(ceiling.lights[0].type, LightType::Point);
    EXPECT_EQ(ceiling.lights[0].position, l.position);
    EXPECT_NEAR(0.5488f - ceiling.lights[0].position.y, 0.001f, 1e-6f);
}

TEST(Cornell, CameraSeesRedOnTheLeft)
{
    const Scene s = makeCornell("cornell-spot");
    const Camera& c = s.camera;
    EXPECT_EQ(c.position, glm::vec3(0.278f, 0.273f, -0.800f));
    EXPECT_EQ(c.forward, glm::vec3(0, 0, 1));
    EXPECT_EQ(c.up, glm::vec3(0, 1, 0));
    EXPECT_NEAR(c.yfovRad * 180.0f / kPi, 39.3077f, 1e-4f);
    EXPECT_EQ(c.znear, 0.01f);
    EXPECT_EQ(c.zfar, 10.0f);
    // Project the wall centres: red left of the image centre, green right.
    const float w = 64.0f;
    const glm::vec3 right = glm::cross(c.forward, c.up);
    EXPECT_LT(glm::dot(centroidOf(meshNamed(s, "left wall")) - c.position, right), 0.0f);
    EXPECT_GT(glm::dot(centroidOf(meshNamed(s, "right wall")) - c.position, right), 0.0f);
    EXPECT_LT(glm::dot(c.rayDirection(0.5f, 0.5f * w, int(w), int(w)), right), 0.0f); // left column looks left
}

TEST(Cornell, UnknownVariantThrows)
{
    EXPECT_THROW(makeCornell("cornell-banana"), SceneError);
}

TEST(SceneLoading, BuiltinNamesAndErrors)
{
    EXPECT_EQ(builtinSceneNames().size(), 8u);
    EXPECT_EQ(loadScene("cornell-spot").contentHash(), makeCornell("cornell-spot").contentHash());
    try {
        loadScene("no-such-scene");
        FAIL() << "expected SceneError";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("no-such-scene"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("cornell-area"), std::string::npos) << "lists what is allowed";
    }
    EXPECT_THROW(loadScene("/nonexistent/folder/scene.gltf"), SceneError);
}

} // namespace
} // namespace bounce::core
