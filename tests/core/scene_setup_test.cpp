// Scene setups (core/scene_setup.h): a glTF made usable by a camera, lights, material overrides and a
// transform; the command-line forms of lights and cameras; refusals that name what is wrong.
#include <cmath>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/gltf_io.h"
#include "core/scene_setup.h"
#include "io_test_util.h"

namespace bounce::core {
namespace {

// The project's own glTF of the canonical box, so that the tests need no downloaded asset.
std::string cornellGltf()
{
    return (test::repoRoot() / "assets" / "cornell-spot.gltf").string();
}

std::string writeSetup(const std::string& name, const std::string& text)
{
    const test::fs::path dir = test::scratchDir();
    const std::string path = (dir / name).string();
    test::writeFile(path, text);
    return path;
}

std::string expectRefused(const std::string& path)
{
    try {
        loadScene(path);
    } catch (const SceneError& e) {
        return e.what();
    }
    ADD_FAILURE() << path << " was accepted";
    return {};
}

TEST(SceneSetup, TransformMaterialsCameraAndLightsApply)
{
    const Scene original = loadGltf(cornellGltf());
    const std::string setup = writeSetup("box.json", R"({
        "gltf": ")" + cornellGltf() + R"(",
        "transform": {"scale": 2.0, "translate": [1, 0, 0]},
        "materials": {"*": {"baseColor": [0.1, 0.2, 0.3], "specular": 0}},
        "camera": {"position": [1.5, 0.5, -2], "target": [1.5, 0.5, 0], "yfovDeg": 50},
        "lights": [{"type": "point", "position": [1.5, 1.0, 0.5], "intensity": 3},
                   {"type": "area", "corner": [1, 1.09, 0], "edge1": [0, 0, 0.5], "edge2": [0.5, 0, 0], "radiance": [4, 4, 4]}]
    })");
    const Scene s = loadScene(setup);
    // Geometry: every position scaled by 2 and moved 1 m along x.
    ASSERT_GE(s.meshes.size(), original.meshes.size());
    for (std::size_t i = 0; i < original.meshes[0].positions.size(); ++i)
        EXPECT_EQ(s.meshes[0].positions[i], 2.0f * original.meshes[0].positions[i] + glm::vec3(1, 0, 0));
    // The glTF's own spot moved with it; the point light was added; the area light became an emitter.
    ASSERT_EQ(s.lights.size(), original.lights.size() + 1);
    EXPECT_EQ(s.lights[0].position, 2.0f * original.lights[0].position + glm::vec3(1, 0, 0));
    EXPECT_EQ(s.lights.back().intensity, glm::vec3(3.0f));
    const Mesh& area = s.meshes.back();
    EXPECT_EQ(s.materials[area.material].emission, glm::vec3(4.0f));
    EXPECT_NEAR(area.normals[0].y, 1.0f, 1e-6f) << "edge1 x edge2 = (0,0,.5) x (.5,0,0) = (0,.25,0)";
    for (std::size_t m = 0; m < original.materials.size(); ++m) {
        EXPECT_EQ(s.materials[m].baseColor, glm::vec3(0.1f, 0.2f, 0.3f));
        EXPECT_EQ(s.materials[m].emission, original.materials[m].emission) << "only the named fields change";
    }
    EXPECT_NEAR(s.camera.yfovRad, 50.0f * kPi / 180.0f, 1e-6f);
    EXPECT_NEAR(s.camera.forward.z, 1.0f, 1e-6f);
    EXPECT_EQ(s.cameraSource, "setup");
}

TEST(SceneSetup, BaseSceneWithAnObjectKeepsTheBaseCamera)
{
    const std::string setup = writeSetup("teapotlike.json", R"({"base": "cornell-area", "gltf": ")" + cornellGltf() +
                                                                R"(", "transform": {"scale": 0.1}})");
    const Scene s = loadScene(setup);
    const Scene base = makeCornell("cornell-area");
    EXPECT_EQ(s.camera.position, base.camera.position);
    EXPECT_GT(s.meshes.size(), base.meshes.size());
    EXPECT_EQ(s.validate(), "");
}

TEST(SceneSetup, RefusalsNameTheProblem)
{
    EXPECT_NE(expectRefused(writeSetup("a.json", R"({"gltf": "no/such/file.gltf"})")).find("no/such/file.gltf"),
              std::string::npos);
    EXPECT_NE(
        expectRefused(writeSetup("b.json", R"({"base": "cornell-spot", "lihgts": []})")).find("unknown key 'lihgts'"),
        std::string::npos);
    EXPECT_NE(expectRefused(writeSetup("c.json", R"({"base": "cornell-spot", "lights": [{"type": "laser"}]})"))
                  .find("unknown light type"),
              std::string::npos);
    EXPECT_NE(
        expectRefused(
            writeSetup(
                "d.json",
                R"({"base": "cornell-spot", "lights": [{"type": "point", "position": [0, 1, 0], "intensity": -1}]})"))
            .find("negative"),
        std::string::npos);
    EXPECT_NE(
        expectRefused(
            writeSetup(
                "e.json",
                R"({"base": "cornell-spot", "lights": [{"type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0], "intensity": 1, "outerDeg": 120}]})"))
            .find("outerDeg"),
        std::string::npos);
    EXPECT_NE(
        expectRefused(
            writeSetup("f.json", R"({"base": "cornell-spot", "camera": {"position": [0, 1, 0], "target": [0, 1, 0]}})"))
            .find("zero length"),
        std::string::npos);
    EXPECT_NE(expectRefused(writeSetup("g.json", R"({"comment": "nothing"})")).find("no geometry"), std::string::npos);
}

TEST(SceneSetup, CommandLineFormsMatchTheJsonForms)
{
    const nlohmann::json l =
        lightJsonFromArgument("spot:position=0.278,0.5,0.279;direction=0,-1,0;intensity=10;outerDeg=30");
    EXPECT_EQ(l["type"], "spot");
    EXPECT_EQ(l["position"], nlohmann::json::array({0.278, 0.5, 0.279}));
    EXPECT_EQ(l["intensity"], 10.0);
    Scene s = makeCornell("cornell-spot");
    const std::size_t before = s.lights.size();
    addLightFromJson(s, l, "--light");
    ASSERT_EQ(s.lights.size(), before + 1);
    EXPECT_NEAR(s.lights.back().outerConeRad, 30.0f * kPi / 180.0f, 1e-6f);

    const nlohmann::json c = cameraJsonFromArgument("0,1,3:0,1,0:40");
    setCameraFromJson(s, c, "--camera");
    EXPECT_EQ(s.camera.position, glm::vec3(0, 1, 3));
    EXPECT_NEAR(s.camera.forward.z, -1.0f, 1e-6f);

    EXPECT_THROW(lightJsonFromArgument("point"), SceneError);
    EXPECT_THROW(lightJsonFromArgument("point:position=1,2"), SceneError);
    EXPECT_THROW(cameraJsonFromArgument("1,2,3"), SceneError);
    EXPECT_THROW(cameraJsonFromArgument("a,b,c:0,0,0"), SceneError);
}

} // namespace
} // namespace bounce::core
