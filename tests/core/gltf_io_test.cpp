// glTF in and out: write -> load gives the same Scene, the committed assets are the generator's scenes,
// node transforms and generated normals follow the glTF rules, and the Khronos validator accepts what
// writeGltf produces.
#include "core/gltf_io.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "gltf_test_builder.h"

namespace bounce::core {
namespace {

using test::json;
using test::fs::path;

// Field-by-field comparison first (readable failures), then the hash that caches rely on.
void expectSameScene(const Scene& expected, const Scene& actual)
{
    ASSERT_EQ(expected.meshes.size(), actual.meshes.size());
    for (std::size_t i = 0; i < expected.meshes.size(); ++i) {
        const Mesh &a = expected.meshes[i], &b = actual.meshes[i];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.positions, b.positions) << a.name;
        EXPECT_EQ(a.normals, b.normals) << a.name;
        EXPECT_EQ(a.uvs, b.uvs) << a.name;
        EXPECT_EQ(a.indices, b.indices) << a.name;
        EXPECT_EQ(a.material, b.material) << a.name;
    }
    ASSERT_EQ(expected.materials.size(), actual.materials.size());
    for (std::size_t i = 0; i < expected.materials.size(); ++i) {
        const Material &a = expected.materials[i], &b = actual.materials[i];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.baseColor, b.baseColor) << a.name;
        EXPECT_EQ(a.baseColorTexture, b.baseColorTexture) << a.name;
        EXPECT_EQ(a.metallic, b.metallic) << a.name;
        EXPECT_EQ(a.roughness, b.roughness) << a.name;
        EXPECT_EQ(a.specular, b.specular) << a.name;
        EXPECT_EQ(a.specularColor, b.specularColor) << a.name;
        EXPECT_EQ(a.emission, b.emission) << a.name;
        EXPECT_EQ(a.doubleSided, b.doubleSided) << a.name;
    }
    ASSERT_EQ(expected.textures.size(), actual.textures.size());
    for (std::size_t i = 0; i < expected.textures.size(); ++i) {
        EXPECT_EQ(expected.textures[i].width, actual.textures[i].width);
        EXPECT_EQ(expected.textures[i].height, actual.textures[i].height);
        EXPECT_EQ(expected.textures[i].rgba8, actual.textures[i].rgba8);
    }
    ASSERT_EQ(expected.lights.size(), actual.lights.size());
    for (std::size_t i = 0; i < expected.lights.size(); ++i) {
        const Light &a = expected.lights[i], &b = actual.lights[i];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.type, b.type) << a.name;
        EXPECT_EQ(a.position, b.position) << a.name;
        EXPECT_EQ(a.direction, b.direction) << a.name;
        EXPECT_EQ(a.intensity, b.intensity) << a.name;
        EXPECT_EQ(a.innerConeRad, b.innerConeRad) << a.name;
        EXPECT_EQ(a.outerConeRad, b.outerConeRad) << a.name;
    }
    EXPECT_EQ(expected.camera.position, actual.camera.position);
    EXPECT_EQ(expected.camera.forward, actual.camera.forward);
    EXPECT_EQ(expected.camera.up, actual.camera.up);
    EXPECT_EQ(expected.camera.yfovRad, actual.camera.yfovRad);
    EXPECT_EQ(expected.camera.znear, actual.camera.znear);
    EXPECT_EQ(expected.camera.zfar, actual.camera.zfar);
    EXPECT_EQ(expected.name, actual.name);
    EXPECT_EQ(expected.contentHash(), actual.contentHash());
}

// A scene that uses every feature the writer knows: texture and uvs, glossy and emissive (<= 1)
// materials, double-sided, a soft spot, a directional light, a camera looking along no axis.
Scene featureScene()
{
    Scene s;
    s.name = "features";
    Texture t;
    t.name = "checker";
    t.width = 3;
    t.height = 2;
    for (int i = 0; i < t.width * t.height; ++i)
        t.rgba8.insert(t.rgba8.end(), {std::uint8_t(40 * i), 200, std::uint8_t(255 - 30 * i), 255});
    s.textures.push_back(t);

    Material textured;
    textured.name = "textured";
    textured.baseColorTexture = 0;
    textured.baseColor = {0.9f, 0.8f, 0.7f};
    Material glossy;
    glossy.name = "glossy";
    glossy.metallic = 0.3f;
    glossy.roughness = 0.4f;
    glossy.specular = 0.5f;
    glossy.specularColor = {0.5f, 1.0f, 0.25f};
    glossy.emission = {0.5f, 0.25f, 0.0f};
    glossy.doubleSided = true;
    s.materials = {textured, glossy};

    Mesh quad;
    quad.name = "quad";
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.normals.assign(4, {0, 0, 1});
    quad.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    Mesh tri;
    tri.name = "tilted";
    tri.positions = {{0.1f, 0.2f, 0.3f}, {1.7f, -0.2f, 0.9f}, {0.3f, 1.1f, -0.4f}};
    const glm::vec3 n =
        glm::normalize(glm::cross(tri.positions[1] - tri.positions[0], tri.positions[2] - tri.positions[0]));
    tri.normals.assign(3, n);
    tri.indices = {0, 1, 2};
    tri.material = 1;
    s.meshes = {quad, tri};

    Light spot;
    spot.name = "soft spot";
    spot.type = LightType::Spot;
    spot.position = {0.5f, 2.0f, 1.0f};
    spot.direction = glm::normalize(glm::vec3(0.2f, -1.0f, -0.3f));
    spot.intensity = {3.0f, 2.5f, 2.0f};
    spot.innerConeRad = 0.3f;
    spot.outerConeRad = 0.6f;
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(1.0f, -2.0f, 0.5f));
    sun.intensity = {0.8f, 0.9f, 1.0f};
    s.lights = {spot, sun};

    s.camera.position = {-1.0f, 0.7f, 3.0f};
    s.camera.forward = glm::normalize(glm::vec3(0.4f, -0.2f, -1.0f));
    const glm::vec3 right = glm::normalize(glm::cross(s.camera.forward, glm::vec3(0, 1, 0)));
    s.camera.up = glm::normalize(glm::cross(right, s.camera.forward));
    s.camera.yfovRad = 0.9f;
    s.camera.znear = 0.05f;
    s.camera.zfar = 50.0f;
    return s;
}

TEST(GltfIo, CornellRoundTripKeepsTheScene)
{
    const path dir = test::scratchDir();
    for (const std::string& name : builtinSceneNames()) {
        SCOPED_TRACE(name);
        const Scene original = makeCornell(name);
        const std::string file = (dir / (name + ".gltf")).string();
        writeGltf(original, file);
        expectSameScene(original, loadGltf(file));
        EXPECT_EQ(original.contentHash(), loadScene(file).contentHash());
    }
}

TEST(GltfIo, FeatureRoundTripKeepsTheScene)
{
    const path dir = test::scratchDir();
    const Scene original = featureScene();
    ASSERT_EQ(original.validate(), "");
    writeGltf(original, (dir / "features.gltf").string());
    expectSameScene(original, loadGltf((dir / "features.gltf").string()));
}

TEST(GltfIo, WriterLeavesNoTemporaryFiles)
{
    const path dir = test::scratchDir();
    writeGltf(makeCornell("cornell-area"), (dir / "a.gltf").string());
    writeGltf(makeCornell("cornell-area"), (dir / "a.gltf").string()); // overwrite
    std::vector<std::string> names;
    for (const auto& e : test::fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"a.bin", "a.gltf"}));
    EXPECT_THROW(writeGltf(makeCornell("cornell-area"), (dir / "a.glb").string()), SceneError);
}

TEST(GltfIo, CommittedAssetsAreTheGeneratorsScenes)
{
    for (const char* name : {"cornell-area", "cornell-spot", "cornell-point"}) {
        SCOPED_TRACE(name);
        const path file = test::repoRoot() / "assets" / (std::string(name) + ".gltf");
        ASSERT_TRUE(test::fs::exists(file)) << file << " (regenerate with bounce_make_assets)";
        expectSameScene(makeCornell(name), loadGltf(file.string()));
    }
}

TEST(GltfIo, NodeHierarchyAndGeneratedFlatNormals)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    b.doc["nodes"] = json::array();
    // parent: translation (1,2,3); children: stretched x2 in x, and mirrored in x.
    b.node({{"translation", {1, 2, 3}}, {"children", {1, 2}}});
    b.node({{"scale", {2, 1, 1}}, {"mesh", 0}});
    b.node({{"scale", {-1, 1, 1}}, {"mesh", 0}});
    b.doc["scenes"] = json::array({{{"nodes", {0}}}});
    const Scene s = loadGltf(b.writeGltf(dir, "tree"));
    ASSERT_EQ(s.meshes.size(), 2u);

    const Mesh& stretched = s.meshes[0];
    EXPECT_EQ(stretched.positions, (std::vector<glm::vec3>{{1, 2, 3}, {3, 2, 3}, {1, 3, 3}}));
    EXPECT_EQ(stretched.indices, (std::vector<std::uint32_t>{0, 1, 2}));
    // The mirror image of a triangle facing +z still faces +z: the winding is flipped back.
    for (const Mesh& m : s.meshes) {
        ASSERT_EQ(m.normals.size(), 3u);
        for (const glm::vec3& n : m.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1)) << m.name;
        const glm::vec3 a = m.positions[m.indices[0]], bb = m.positions[m.indices[1]], c = m.positions[m.indices[2]];
        EXPECT_GT(glm::cross(bb - a, c - a).z, 0.0f) << "counter-clockwise seen from the normal's side";
    }
    const Mesh& mirrored = s.meshes[1];
    for (const glm::vec3& p : {glm::vec3(1, 2, 3), glm::vec3(0, 2, 3), glm::vec3(1, 3, 3)})
        EXPECT_NE(std::find(mirrored.positions.begin(), mirrored.positions.end(), p), mirrored.positions.end());

    // No material: glTF's default one (metallic 1, roughness 1, white).
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materials[0].metallic, 1.0f);
    EXPECT_EQ(s.materials[0].roughness, 1.0f);
    EXPECT_EQ(s.materials[0].baseColor, glm::vec3(1.0f));
    EXPECT_EQ(s.meshes[0].material, 0u);
}

TEST(GltfIo, IndexedTrianglesWithoutNormalsAreSplitFlat)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b;
    // A quad folded along its diagonal: two faces with different normals, shared vertices.
    const int pos = b.positions({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, -1});
    const int idx = b.indices({0, 1, 2, 0, 3, 1});
    b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}});
    b.node({{"mesh", 0}});
    const Scene s = loadGltf(b.writeGltf(dir, "folded"));
    ASSERT_EQ(s.meshes.size(), 1u);
    const Mesh& m = s.meshes[0];
    ASSERT_EQ(m.positions.size(), 6u) << "each triangle gets its own vertices";
    EXPECT_EQ(m.normals[0], glm::vec3(0, 0, 1));
    EXPECT_EQ(m.normals[3], glm::vec3(0, -1, 0));
}

TEST(GltfIo, NormalsUseTheInverseTranspose)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b;
    const float r = std::sqrt(0.5f);
    const int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int nrm = b.normals({r, r, 0, r, r, 0, r, r, 0});
    b.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}});
    // Column-major: rotation of 90 degrees about x, then translation (0,0,5), on a node scaled (2,1,1).
    b.node({{"matrix", {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 5, 1}}, {"children", {1}}});
    b.node({{"scale", {2, 1, 1}}, {"mesh", 0}});
    b.doc["scenes"] = json::array({{{"nodes", {0}}}});
    const Scene s = loadGltf(b.writeGltf(dir, "normals"));
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].positions[1], glm::vec3(2, 0, 5));
    EXPECT_EQ(s.meshes[0].positions[2], glm::vec3(0, 0, 6));
    // Scale (2,1,1) turns the normal (1,1,0) into (1/2,1,0); the rotation takes y to z.
    const glm::vec3 expected = glm::normalize(glm::vec3(0.5f, 0.0f, 1.0f));
    for (const glm::vec3& n : s.meshes[0].normals) {
        EXPECT_NEAR(n.x, expected.x, 1e-6f);
        EXPECT_NEAR(n.y, expected.y, 1e-6f);
        EXPECT_NEAR(n.z, expected.z, 1e-6f);
    }
}

TEST(GltfIo, LightsCameraAndSkippedPrimitives)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    const int pos = b.positions({0, 0, 0, 1, 0, 0});
    b.doc["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", pos}}}, {"mode", 1}}); // LINES: skipped
    b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "spot"},
         {"name", "s"},
         {"color", {1.0, 0.5, 0.25}},
         {"intensity", 4.0},
         {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
        {{"type", "directional"}, {"intensity", 2.0}}};
    // Rotation of -90 degrees about x: the node's -z axis points down.
    const double h = std::sqrt(0.5);
    b.node({{"translation", {1, 2, 3}},
            {"rotation", {-h, 0, 0, h}},
            {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    b.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}};
    b.node({{"translation", {0, 0, 4}}, {"camera", 0}});
    b.doc["scenes"][0]["nodes"] = {0, 1, 2, 3};
    const Scene s = loadGltf(b.writeGltf(dir, "lights"));

    EXPECT_EQ(s.triangleCount(), 1u);
    ASSERT_EQ(s.lights.size(), 2u);
    const Light& spot = s.lights[0];
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_EQ(spot.position, glm::vec3(1, 2, 3));
    EXPECT_NEAR(glm::distance(spot.direction, glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
    EXPECT_EQ(spot.intensity, glm::vec3(4.0f, 2.0f, 1.0f));
    EXPECT_EQ(spot.innerConeRad, 0.2f);
    EXPECT_EQ(spot.outerConeRad, 0.5f);
    EXPECT_EQ(s.lights[1].type, LightType::Directional);
    EXPECT_EQ(s.lights[1].direction, glm::vec3(0, 0, -1));
    EXPECT_EQ(s.lights[1].intensity, glm::vec3(2.0f));

    // The camera node is unrotated: it looks along -z. Without zfar the far plane still covers the scene.
    EXPECT_EQ(s.camera.position, glm::vec3(0, 0, 4));
    EXPECT_EQ(s.camera.forward, glm::vec3(0, 0, -1));
    EXPECT_EQ(s.camera.up, glm::vec3(0, 1, 0));
    EXPECT_EQ(s.camera.yfovRad, 0.5f);
    EXPECT_EQ(s.camera.znear, 0.1f);
    EXPECT_TRUE(std::isfinite(s.camera.zfar));
    EXPECT_GT(s.camera.zfar, 4.0f);
}

TEST(GltfIo, DefaultCameraFramesTheScene)
{
    const path dir = test::scratchDir();
    const Scene s = loadGltf(test::oneTriangle().writeGltf(dir, "nocamera"));
    EXPECT_EQ(s.camera.forward, glm::vec3(0, 0, 1));
    EXPECT_EQ(s.camera.up, glm::vec3(0, 1, 0));
    EXPECT_LT(s.camera.position.z, 0.0f);
    // Every corner of the triangle is inside the view frustum.
    for (const glm::vec3& p : s.meshes[0].positions) {
        const glm::vec4 clip = s.camera.projection(1.0f) * s.camera.view() * glm::vec4(p, 1.0f);
        EXPECT_LE(std::abs(clip.x), clip.w * 1.0001f);
        EXPECT_LE(std::abs(clip.y), clip.w * 1.0001f);
        EXPECT_LE(std::abs(clip.z), clip.w);
    }
}

TEST(GltfIo, GlbLoadsLikeGltf)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    const Scene fromGltf = loadGltf(b.writeGltf(dir, "t"));
    const Scene fromGlb = loadGltf(b.writeGlb(dir, "t"));
    EXPECT_EQ(fromGltf.contentHash(), fromGlb.contentHash());
    EXPECT_EQ(fromGlb.triangleCount(), 1u);
}

// ---- the Khronos glTF validator --------------------------------------------------------------------

bool commandExists(const std::string& name)
{
    return std::system(("command -v " + name + " >/dev/null 2>&1").c_str()) == 0;
}

TEST(GltfValidator, WrittenFilesHaveNoErrors)
{
    const path root = test::repoRoot();
    // Not a skip: scripts/install-deps.sh installs both, so a missing one is a broken setup.
    ASSERT_TRUE(commandExists("node")) << "node is not installed; scripts/install-deps.sh installs it";
    ASSERT_TRUE(test::fs::exists(root / "node_modules" / "gltf-validator"))
        << "node_modules/gltf-validator is missing; run `npm ci` in " << root;

    const path dir = test::scratchDir();
    writeGltf(makeCornell("cornell-point-ceiling"), (dir / "cornell-point-ceiling.gltf").string());
    writeGltf(featureScene(), (dir / "features.gltf").string());
    std::vector<path> files = {dir / "cornell-point-ceiling.gltf", dir / "features.gltf"};
    for (const char* name : {"cornell-area", "cornell-spot", "cornell-point"})
        files.push_back(root / "assets" / (std::string(name) + ".gltf"));

    std::string command = "node '" + (root / "tests" / "core" / "validate_gltf.mjs").string() + "'";
    for (const path& f : files) command += " '" + f.string() + "'";
    command += " > '" + (dir / "report.json").string() + "'";
    const int status = std::system(command.c_str());
    const std::string text = test::readFile(dir / "report.json");
    ASSERT_FALSE(text.empty()) << "validator printed nothing (status " << status << ")";
    const json report = json::parse(text);
    ASSERT_EQ(report["files"].size(), files.size());
    for (const json& r : report["files"]) {
        EXPECT_EQ(r["errors"].get<int>(), 0) << r.dump(2);
        for (const json& m : r["messages"])
            std::cout << r["file"].get<std::string>() << ": " << m["severity"].get<std::string>() << " "
                      << m["code"].get<std::string>() << " at " << m["pointer"].dump() << ": "
                      << m["message"].get<std::string>() << "\n";
    }
}

} // namespace
} // namespace bounce::core
