// glTF normal maps in and out (issue 59): normalTexture and its scale, TANGENT, tangents computed from the uvs
// where a file has none (with the v axis as glTF has it), a map without uvs ignored with a warning, a
// mirroring node flipping the handedness, setups merging scenes with maps, and the content hash: keys of
// scenes without maps as they were, a map or a tangent changing the key.
#include <cmath>
#include <functional>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/gltf_io.h"
#include "core/scene.h"
#include "io_test_util.h"

namespace bounce::core {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// A 2 m square at y = 0 facing +y, u = (x + 1) / 2, v = (z + 1) / 2: dP/du = +x, the image's +y (-dP/dv)
// is -z, so its tangent is (1, 0, 0) with w = +1. A 2x2 normal map, scale 0.75.
Scene mappedPlane()
{
    Scene s;
    Texture t;
    t.name = "normals";
    t.width = t.height = 2;
    t.rgba8 = {128, 128, 255, 255, 200, 128, 230, 255, 128, 60, 240, 255, 90, 170, 220, 255};
    s.textures.push_back(t);
    Material m;
    m.name = "mapped";
    m.normalTexture = 0;
    m.normalScale = 0.75f;
    s.materials.push_back(m);
    Mesh plane;
    plane.name = "plane";
    plane.positions = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
    plane.normals.assign(4, glm::vec3(0, 1, 0));
    for (const glm::vec3& p : plane.positions) plane.uvs.push_back({(p.x + 1.0f) * 0.5f, (p.z + 1.0f) * 0.5f});
    plane.tangents.assign(4, glm::vec4(1, 0, 0, 1));
    plane.indices = {0, 1, 2, 0, 2, 3};
    s.meshes.push_back(plane);
    return s;
}

json readJson(const fs::path& p)
{
    return json::parse(test::readFile(p.string()));
}

// Writes the scene, lets `edit` change the .gltf's JSON, loads it back; the loader's warnings in `warnings`.
Scene roundTrip(const Scene& scene, const std::function<void(json&)>& edit, std::string* warnings = nullptr)
{
    const fs::path dir = test::scratchDir();
    const fs::path file = dir / "mapped.gltf";
    writeGltf(scene, file.string());
    json doc = readJson(file);
    edit(doc);
    test::writeFile(file.string(), doc.dump());
    ::testing::internal::CaptureStderr();
    Scene back = loadGltf(file.string());
    const std::string err = ::testing::internal::GetCapturedStderr();
    if (warnings) *warnings = err;
    return back;
}

TEST(NormalMapIo, NormalTextureScaleAndTangentsComeBackAsWritten)
{
    const Scene s = mappedPlane();
    std::string warnings;
    const Scene back = roundTrip(
        s, [](json&) {}, &warnings);
    EXPECT_EQ(warnings, "");
    ASSERT_EQ(back.materials.size(), 1u);
    EXPECT_EQ(back.materials[0].normalTexture, 0);
    EXPECT_EQ(back.materials[0].normalScale, 0.75f);
    ASSERT_EQ(back.textures.size(), 1u);
    EXPECT_EQ(back.textures[0].rgba8, s.textures[0].rgba8) << "a normal map's bytes are not colour-converted";
    ASSERT_EQ(back.meshes.size(), 1u);
    EXPECT_EQ(back.meshes[0].tangents, s.meshes[0].tangents);
    EXPECT_TRUE(back.hasNormalMaps());
    EXPECT_EQ(back.contentHash(), s.contentHash());
}

TEST(NormalMapIo, TangentsComputedFromTheUvsWhereTheFileHasNone)
{
    const Scene s = mappedPlane();
    std::string warnings;
    const Scene back = roundTrip(
        s, [](json& doc) { doc["meshes"][0]["primitives"][0]["attributes"].erase("TANGENT"); }, &warnings);
    EXPECT_NE(warnings.find("tangents computed from TEXCOORD_0"), std::string::npos) << warnings;
    ASSERT_EQ(back.meshes[0].tangents.size(), 4u);
    for (const glm::vec4& t : back.meshes[0].tangents) EXPECT_EQ(t, glm::vec4(1, 0, 0, 1));

    // v running the other way (the image's +y now +z): the handedness flips, the tangent stays.
    Mesh flipped = s.meshes[0];
    for (glm::vec2& uv : flipped.uvs) uv.y = 1.0f - uv.y;
    for (const glm::vec4& t : tangentsFromUvs(flipped)) EXPECT_EQ(t, glm::vec4(1, 0, 0, -1));
}

// Hard cases of the computed tangents: a triangle whose uvs coincide (no uv area) and a vertex normal
// tilted off the triangle's: still unit, orthogonal to the vertex normal, finite.
TEST(NormalMapIo, ComputedTangentsStayUnitAndOrthogonalOnDegenerateUvs)
{
    Mesh m = mappedPlane().meshes[0];
    m.uvs.assign(4, glm::vec2(0.5f));
    m.normals[2] = glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f));
    const std::vector<glm::vec4> tangents = tangentsFromUvs(m);
    ASSERT_EQ(tangents.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        const glm::vec3 t(tangents[i]);
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f) << i;
        EXPECT_NEAR(glm::dot(t, m.normals[i]), 0.0f, 1e-5f) << i;
        EXPECT_TRUE(tangents[i].w == 1.0f || tangents[i].w == -1.0f) << i;
    }
}

TEST(NormalMapIo, MapWithoutUvsIsIgnoredWithAWarning)
{
    std::string warnings;
    const Scene back = roundTrip(
        mappedPlane(),
        [](json& doc) {
            json& attributes = doc["meshes"][0]["primitives"][0]["attributes"];
            attributes.erase("TANGENT");
            attributes.erase("TEXCOORD_0");
        },
        &warnings);
    EXPECT_NE(warnings.find("a normal map without TEXCOORD_0"), std::string::npos) << warnings;
    EXPECT_TRUE(back.meshes[0].tangents.empty());
    EXPECT_FALSE(back.hasNormalMaps());
}

// A node that mirrors x: the tangent follows the model matrix (-x), and the handedness flips so that the
// bitangent w cross(n, t) stays the image's +y (-z).
TEST(NormalMapIo, MirroringNodeFlipsTheHandedness)
{
    const Scene back = roundTrip(mappedPlane(), [](json& doc) {
        for (json& node : doc["nodes"])
            if (node.contains("mesh")) node["scale"] = {-1.0, 1.0, 1.0};
    });
    ASSERT_EQ(back.meshes[0].tangents.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        const glm::vec4 t = back.meshes[0].tangents[i];
        EXPECT_EQ(glm::vec3(t), glm::vec3(-1, 0, 0)) << i;
        EXPECT_EQ(t.w, -1.0f) << i;
        const glm::vec3 bitangent = t.w * glm::cross(back.meshes[0].normals[i], glm::vec3(t));
        EXPECT_EQ(bitangent, glm::vec3(0, 0, -1)) << i;
    }
}

TEST(NormalMapIo, ContentHashCoversMapsAndTangentsOnlyWhereThereAreSome)
{
    const Scene s = mappedPlane();
    Scene other = s;
    other.materials[0].normalScale = 0.5f;
    EXPECT_NE(other.contentHash(), s.contentHash());
    other = s;
    other.meshes[0].tangents[0].w = -1.0f;
    EXPECT_NE(other.contentHash(), s.contentHash());
    other = s;
    dropNormalMaps(other);
    EXPECT_NE(other.contentHash(), s.contentHash());
    EXPECT_FALSE(other.hasNormalMaps());

    // Without maps the key is what it was before the fields existed: the scene's other fields alone. A
    // scene without tangents and maps hashes the same as one whose empty fields are set to their defaults.
    Scene plain = s;
    plain.materials[0].normalTexture = -1;
    plain.meshes[0].tangents.clear();
    Scene plainScaled = plain;
    plainScaled.materials[0].normalScale = 3.0f; // not read without a map
    EXPECT_EQ(plain.contentHash(), plainScaled.contentHash());
}

TEST(NormalMapIo, ValidateRefusesBrokenTangentsAndMapIndices)
{
    Scene s = mappedPlane();
    s.meshes[0].tangents.pop_back();
    EXPECT_NE(s.validate().find("tangents for"), std::string::npos) << s.validate();
    s = mappedPlane();
    s.meshes[0].tangents[1].x = std::nanf("");
    EXPECT_NE(s.validate().find("tangent not finite"), std::string::npos) << s.validate();
    s = mappedPlane();
    s.meshes[0].tangents[1].w = 0.5f;
    EXPECT_NE(s.validate().find("handedness"), std::string::npos) << s.validate();
    s = mappedPlane();
    s.materials[0].normalTexture = 3;
    EXPECT_NE(s.validate().find("normal texture index out of range"), std::string::npos) << s.validate();
    EXPECT_EQ(mappedPlane().validate(), "");
}

} // namespace
} // namespace bounce::core
