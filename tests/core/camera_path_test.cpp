// Camera paths (core/camera_path.h): linear interpolation between keys and holding outside them against
// closed-form values, the lights entries from their frame on, and each refusal naming its problem.
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/camera_path.h"
#include "io_test_util.h"

namespace bounce::core {
namespace {

using nlohmann::json;

void expectVec(const glm::vec3& got, const glm::vec3& want, const std::string& what)
{
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], 1e-6f) << what << " [" << i << "]";
}

// Two keys, frames 2 and 6 of 10: held before 2 and after 6, linear between.
CameraPath twoKeys()
{
    return parseCameraPath(json::parse(R"({"frames": 10, "keys": [
        {"frame": 2, "camera": "0,1,0:0,1,4:30"},
        {"frame": 6, "camera": "4,1,0:0,1,8:70"}]})"),
                           "test");
}

TEST(CameraPath, InterpolatesLinearlyBetweenKeys)
{
    const CameraPath p = twoKeys();
    EXPECT_EQ(p.frames, 10);
    // Frame 4 is halfway (t = 1/2), frame 3 a quarter (t = 1/4).
    expectVec(p.at(4).position, {2, 1, 0}, "frame 4 position");
    expectVec(p.at(4).target, {0, 1, 6}, "frame 4 target");
    EXPECT_NEAR(p.at(4).yfovDeg, 50.0f, 1e-5f);
    expectVec(p.at(3).position, {1, 1, 0}, "frame 3 position");
    expectVec(p.at(3).target, {0, 1, 5}, "frame 3 target");
    EXPECT_NEAR(p.at(3).yfovDeg, 40.0f, 1e-5f);
    // The camera: forward toward the target, up +y, the field of view in radians, near and far from the base.
    Camera base;
    base.znear = 0.05f;
    base.zfar = 33.0f;
    const Camera c = p.camera(4, base);
    expectVec(c.position, {2, 1, 0}, "camera position");
    expectVec(c.forward, glm::vec3(-2, 0, 6) / std::sqrt(40.0f), "camera forward");
    expectVec(c.up, {0, 1, 0}, "camera up");
    EXPECT_NEAR(c.yfovRad, 50.0f * 3.14159265f / 180.0f, 1e-6f);
    EXPECT_EQ(c.znear, 0.05f);
    EXPECT_EQ(c.zfar, 33.0f);
}

TEST(CameraPath, HoldsBeforeTheFirstKeyAndAfterTheLast)
{
    const CameraPath p = twoKeys();
    for (int f : {0, 1, 2}) {
        expectVec(p.at(f).position, {0, 1, 0}, "frame " + std::to_string(f));
        expectVec(p.at(f).target, {0, 1, 4}, "frame " + std::to_string(f));
        EXPECT_EQ(p.at(f).yfovDeg, 30.0f) << f;
    }
    for (int f : {6, 7, 9}) {
        expectVec(p.at(f).position, {4, 1, 0}, "frame " + std::to_string(f));
        expectVec(p.at(f).target, {0, 1, 8}, "frame " + std::to_string(f));
        EXPECT_EQ(p.at(f).yfovDeg, 70.0f) << f;
    }
    // One key: every frame is that key.
    const CameraPath one = parseCameraPath(json::parse(R"({"frames": 3, "keys": [
        {"frame": 1, "camera": "1,2,3:1,2,4:45"}]})"),
                                           "test");
    for (int f = 0; f < 3; ++f) expectVec(one.at(f).position, {1, 2, 3}, "one key, frame " + std::to_string(f));
}

TEST(CameraPath, LightsReplaceTheScenesFromTheirFrameOn)
{
    const CameraPath p = parseCameraPath(json::parse(R"({"frames": 10,
        "keys": [{"frame": 0, "camera": "0,1,0:0,1,4:30"}],
        "lights": [{"frame": 3, "light": ["point:position=1,2,3;intensity=5"]},
                   {"frame": 7, "light": ["spot:position=0,1,0;direction=0,-1,0;intensity=2;outerDeg=30",
                                          "directional:direction=0,-1,0;irradiance=4"]}]})"),
                                         "test");
    EXPECT_EQ(p.lightsAt(0), nullptr);
    EXPECT_EQ(p.lightsAt(2), nullptr);
    for (int f : {3, 6}) {
        ASSERT_NE(p.lightsAt(f), nullptr) << f;
        ASSERT_EQ(p.lightsAt(f)->size(), 1u) << f;
        EXPECT_EQ(p.lightsAt(f)->at(0).type, LightType::Point);
        expectVec(p.lightsAt(f)->at(0).position, {1, 2, 3}, "point");
        expectVec(p.lightsAt(f)->at(0).intensity, {5, 5, 5}, "point intensity");
    }
    ASSERT_NE(p.lightsAt(9), nullptr);
    ASSERT_EQ(p.lightsAt(9)->size(), 2u);
    EXPECT_EQ(p.lightsAt(9)->at(0).type, LightType::Spot);
    EXPECT_NEAR(p.lightsAt(9)->at(0).outerConeRad, 30.0f * 3.14159265f / 180.0f, 1e-6f);
    EXPECT_EQ(p.lightsAt(9)->at(1).type, LightType::Directional);
    EXPECT_TRUE(p.lightsChangeAt(3));
    EXPECT_FALSE(p.lightsChangeAt(4));
    EXPECT_TRUE(p.lightsChangeAt(7));
}

// Each bad path: refused with CameraPathError whose message names the problem.
TEST(CameraPath, RefusesBadPathsNamingTheProblem)
{
    const std::string key0 = R"({"frame": 0, "camera": "0,1,0:0,1,4:40"})";
    const struct {
        std::string text, says;
    } cases[] = {
        {R"({"frames": 4, "keys": [{"frame": 0, "camera": "nan,1,0:0,1,4:40"}]})", "not finite"},
        {R"({"frames": 4, "keys": [{"frame": 0, "camera": "0,1,0:0,inf,4:40"}]})", "not finite"},
        {R"({"frames": 4, "keys": [{"frame": 0, "camera": "0,1,0:0,1,4:nan"}]})", "not finite"},
        // A zero-length view at a key, and one between two keys that are fine (frame 1 of 0..4: t = 1/4).
        {R"({"frames": 4, "keys": [{"frame": 0, "camera": "0,1,2:0,1,2:40"}]})", "zero-length"},
        {R"({"frames": 5, "keys": [{"frame": 0, "camera": "0,1,0:0,1,2:40"},
                                   {"frame": 4, "camera": "0,1,4:0,1,-2:40"}]})",
         "frame 1: the position equals the target: a zero-length view"},
        {R"({"frames": 8, "keys": [)" + key0 + R"(, {"frame": 0, "camera": "0,1,0:0,1,5:40"}]})", "strictly increase"},
        {R"({"frames": 8, "keys": [{"frame": 5, "camera": "0,1,0:0,1,5:40"}, )" + key0 + "]}", "strictly increase"},
        {R"({"frames": 0, "keys": [)" + key0 + "]}", "'frames' is 0, outside 1..100000"},
        {R"({"frames": 2.5, "keys": [)" + key0 + "]}", "'frames' needs an integer"},
        {R"({"keys": [)" + key0 + "]}", "'frames' is missing"},
        {R"({"frames": 4})", "'keys' is missing"},
        {R"({"frames": 4, "keys": []})", "at least one"},
        {R"({"frames": 4, "keys": [{"frame": 0}]})", "'camera' is missing"},
        {R"({"frames": 4, "keys": [{"camera": "0,1,0:0,1,4:40"}]})", "'frame' is missing"},
        {R"({"frames": 4, "keys": [{"frame": 0, "camera": "0,1,0:0,1,4"}]})", "needs its field of view"},
        {R"({"frames": 4, "keys": [{"frame": 4, "camera": "0,1,0:0,1,4:40"}]})", "'frame' is 4, outside 0..3"},
        {R"({"frames": 4, "keys": [{"frame": -1, "camera": "0,1,0:0,1,4:40"}]})", "outside 0..3"},
        {R"({"frames": 4, "keys": [{"frame": 0, "camera": "0,1,0:0,1,4:180"}]})", "'yfovDeg' must be in (0, 180)"},
        {R"({"frames": 4, "keys": [{"frame": 0, "camera": "0,1,0:0,5,0:40"}]})", "parallel"},
        {R"({"frames": 4, "keys": [)" + key0 + R"(], "speed": 2})", "unknown key 'speed'"},
        {R"({"frames": 4, "keys": [)" + key0 +
             R"(], "lights": [{"frame": 1, "light": ["point:position=nan,1,0;intensity=1"]}]})",
         "not finite"},
        {R"({"frames": 4, "keys": [)" + key0 +
             R"(], "lights": [{"frame": 1, "light": ["area:corner=0,1,0;edge1=1,0,0;edge2=0,0,1;radiance=1"]}]})",
         "an area light is geometry"},
        {R"({"frames": 4, "keys": [)" + key0 +
             R"(], "lights": [{"frame": 2, "light": []}, {"frame": 1, "light": []}]})",
         "'lights' frames must strictly increase"},
        {R"({"frames": 4, "keys": [)" + key0 + R"(], "lights": [{"frame": 1, "light": "point:position=0,1,0"}]})",
         "'light' needs an array"},
    };
    for (const auto& c : cases) {
        try {
            parseCameraPath(json::parse(c.text), "p.json");
            ADD_FAILURE() << "accepted: " << c.text;
        } catch (const CameraPathError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(c.says), std::string::npos) << c.text << "\n  said: " << what;
            EXPECT_EQ(what.rfind("p.json: ", 0), 0u) << "names the file first: " << what;
        }
    }
}

TEST(CameraPath, LoadRefusesMalformedJsonAndMissingFiles)
{
    const test::fs::path dir = test::scratchDir();
    test::writeFile(dir / "bad.json", R"({"frames": 4, "keys": [)");
    EXPECT_THROW(loadCameraPath((dir / "bad.json").string()), CameraPathError);
    EXPECT_THROW(loadCameraPath((dir / "none.json").string()), CameraPathError);
    test::writeFile(dir / "good.json", R"({"frames": 2, "keys": [{"frame": 0, "camera": "0,1,0:0,1,4:40"}]})");
    EXPECT_EQ(loadCameraPath((dir / "good.json").string()).frames, 2);
}

} // namespace
} // namespace bounce::core
