// The reference cache: a miss renders and stores EXR + JSON, a hit returns the same image without
// rendering, the key follows what changes the result (and not the thread count), and a damaged entry
// is rendered again. Runs in a temporary folder, never in the user's cache.
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/ref/test_scenes.h"

namespace {

using namespace bounce;
using namespace bounce::testing;
namespace fs = std::filesystem;

struct TempDir {
    fs::path path;
    TempDir() : path(fs::temp_directory_path() / ("bounce-ref-cache-" + std::to_string(getpid())))
    {
        fs::remove_all(path);
    }
    ~TempDir() { fs::remove_all(path); }
};

TEST(Cache, MissThenHit)
{
    const TempDir dir;
    const core::Scene s = boxRoom(true);
    const ref::RenderSettings rs = settings(ref::LightPaths::Direct, 8, 4);
    const ref::RenderResult first = ref::cachedReference(s, s.camera, rs, dir.path.string());
    EXPECT_FALSE(first.fromCache);
    const std::string key = ref::cacheKey(s, s.camera, rs);
    ASSERT_TRUE(fs::exists(dir.path / (key + ".exr")));
    ASSERT_TRUE(fs::exists(dir.path / (key + ".json")));
    std::ifstream in(dir.path / (key + ".json"));
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j.at("spp").get<int>(), 4);
    EXPECT_EQ(j.at("paths").get<std::string>(), "direct");
    EXPECT_GT(j.at("raysPerSecond").get<double>(), 0.0);

    const ref::RenderResult second = ref::cachedReference(s, s.camera, rs, dir.path.string());
    EXPECT_TRUE(second.fromCache);
    EXPECT_EQ(second.image.rgb, first.image.rgb); // 32-bit float EXR: exact
    EXPECT_EQ(second.spp, first.spp);
    EXPECT_EQ(second.rays, first.rays);
}

TEST(Cache, KeyFollowsWhatChangesTheResult)
{
    const core::Scene s = boxRoom(true);
    const ref::RenderSettings base = settings(ref::LightPaths::Direct, 8, 4);
    const std::string k = ref::cacheKey(s, s.camera, base);
    ref::RenderSettings t = base;
    t.threads = 1;
    EXPECT_EQ(ref::cacheKey(s, s.camera, t), k); // threads change nothing
    t.progress = !t.progress;
    EXPECT_EQ(ref::cacheKey(s, s.camera, t), k);
    for (int change = 0; change < 6; ++change) {
        ref::RenderSettings c = base;
        core::Camera cam = s.camera;
        core::Scene scene = s;
        switch (change) {
        case 0: c.spp = 5; break;
        case 1: c.paths = ref::LightPaths::Full; break;
        case 2: c.width = 9; break;
        case 3: c.seed = 2; break;
        case 4: cam.position.x += 0.01f; break;
        case 5: scene.materials[0].baseColor.x = 0.1f; break;
        }
        EXPECT_NE(ref::cacheKey(scene, cam, c), k) << "change " << change;
    }
}

TEST(Cache, DamagedEntryIsRenderedAgain)
{
    const TempDir dir;
    const core::Scene s = boxRoom(true);
    const ref::RenderSettings rs = settings(ref::LightPaths::Direct, 8, 2);
    ref::cachedReference(s, s.camera, rs, dir.path.string());
    const std::string key = ref::cacheKey(s, s.camera, rs);
    {
        std::ofstream(dir.path / (key + ".json")) << "{ not json";
    }
    EXPECT_FALSE(ref::cachedReference(s, s.camera, rs, dir.path.string()).fromCache);
    EXPECT_TRUE(ref::cachedReference(s, s.camera, rs, dir.path.string()).fromCache);
    fs::remove(dir.path / (key + ".exr"));
    EXPECT_FALSE(ref::cachedReference(s, s.camera, rs, dir.path.string()).fromCache);
}

TEST(Cache, DefaultFolderHonoursBounceCache)
{
    const char* old = std::getenv("BOUNCE_CACHE");
    const std::string saved = old ? old : "";
    setenv("BOUNCE_CACHE", "/tmp/some-bounce-cache", 1);
    EXPECT_EQ(ref::defaultCacheDir(), "/tmp/some-bounce-cache");
    unsetenv("BOUNCE_CACHE");
    EXPECT_NE(ref::defaultCacheDir().find("references"), std::string::npos);
    if (old) setenv("BOUNCE_CACHE", saved.c_str(), 1);
}

} // namespace
