// The reference cache: a miss renders and stores EXR + JSON, a hit returns the same image without
// rendering, the key follows what changes the result (and not the thread count) including the path
// tracer's own code, a damaged entry (truncated, bytes flipped, files of two renders) is rendered again and
// never trusted, and concurrent writers of one entry (threads, processes) leave one intact entry. Runs in
// a temporary folder, never in the user's cache.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <sys/wait.h>
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

// The box room with everything the key must follow: an area light, a point and a spot light, and a
// texture on the floor's material.
core::Scene keyedScene()
{
    core::Scene s = boxRoom(true);
    core::Light point;
    point.position = {0.5f, 0.8f, 0.5f};
    point.intensity = glm::vec3(0.3f);
    core::Light spot = point;
    spot.type = core::LightType::Spot;
    spot.innerConeRad = 0.2f;
    spot.outerConeRad = 0.6f;
    s.lights = {point, spot};
    core::Texture t;
    t.width = t.height = 2;
    t.rgba8.assign(2 * 2 * 4, 200);
    s.textures.push_back(t);
    s.materials[0].baseColorTexture = 0;
    for (core::Mesh& m : s.meshes) m.uvs.assign(m.positions.size(), glm::vec2(0.5f));
    return s;
}

TEST(Cache, KeyFollowsWhatChangesTheResult)
{
    const core::Scene s = keyedScene();
    ASSERT_EQ(s.validate(), "");
    ref::RenderSettings base = settings(ref::LightPaths::Direct, 8, 4);
    const std::string k = ref::cacheKey(s, s.camera, base);
    ref::RenderSettings t = base;
    t.threads = 1;
    EXPECT_EQ(ref::cacheKey(s, s.camera, t), k); // threads change nothing
    t.progress = !t.progress;
    EXPECT_EQ(ref::cacheKey(s, s.camera, t), k);
    const char* changes[] = {"spp",
                             "paths",
                             "width",
                             "height",
                             "seed",
                             "noise target",
                             "camera position",
                             "camera direction",
                             "camera up",
                             "field of view",
                             "material colour",
                             "vertex position",
                             "index",
                             "normal",
                             "texture coordinate",
                             "one more mesh",
                             "light intensity",
                             "light position",
                             "light direction",
                             "spot cone",
                             "light type",
                             "one more light",
                             "texel",
                             "texture size",
                             "emission"};
    for (const char* change : changes) {
        ref::RenderSettings c = base;
        core::Camera cam = s.camera;
        core::Scene scene = s;
        const std::string what = change;
        if (what == "spp") c.spp = 5;
        if (what == "paths") c.paths = ref::LightPaths::Full;
        if (what == "width") c.width = 9;
        if (what == "height") c.height = 9;
        if (what == "seed") c.seed = 2;
        if (what == "noise target") c.targetNoise = 0.05;
        if (what == "camera position") cam.position.x += 0.01f;
        if (what == "camera direction") cam.forward = glm::normalize(cam.forward + glm::vec3(0.01f, 0.0f, 0.0f));
        if (what == "camera up") cam.up = glm::normalize(cam.up + glm::vec3(0.0f, 0.0f, 0.01f));
        if (what == "field of view") cam.yfovRad *= 1.01f;
        if (what == "material colour") scene.materials[0].baseColor.x = 0.1f;
        if (what == "vertex position") scene.meshes[2].positions[1].y += 0.001f;
        if (what == "index") std::swap(scene.meshes[0].indices[0], scene.meshes[0].indices[1]);
        if (what == "normal") scene.meshes[0].normals[0] = glm::normalize(glm::vec3(0.01f, 1.0f, 0.0f));
        if (what == "texture coordinate") scene.meshes[0].uvs[0].x = 0.25f;
        if (what == "one more mesh") scene.meshes.push_back(scene.meshes[0]);
        if (what == "light intensity") scene.lights[0].intensity.y *= 1.01f;
        if (what == "light position") scene.lights[0].position.z += 0.01f;
        if (what == "light direction") scene.lights[1].direction = glm::normalize(glm::vec3(0.01f, -1.0f, 0.0f));
        if (what == "spot cone") scene.lights[1].outerConeRad = 0.61f;
        if (what == "light type") scene.lights[0].type = core::LightType::Directional;
        if (what == "one more light") scene.lights.push_back(scene.lights[0]);
        if (what == "texel") scene.textures[0].rgba8[5] = 201;
        if (what == "texture size") scene.textures[0].width = 4, scene.textures[0].height = 1;
        if (what == "emission") scene.materials.back().emission.z *= 1.01f;
        EXPECT_NE(ref::cacheKey(scene, cam, c), k) << "changing the " << what << " keeps the key";
    }
    // Path depth is part of the full light paths only (the others have a fixed number of reflections).
    base.paths = ref::LightPaths::Full;
    ref::RenderSettings deeper = base;
    deeper.maxDepth = 3;
    EXPECT_NE(ref::cacheKey(s, s.camera, deeper), ref::cacheKey(s, s.camera, base)) << "path depth";
    // minSpp counts when there is a noise target, and only then.
    base.targetNoise = 0.05;
    ref::RenderSettings moreSamples = base;
    moreSamples.minSpp = 32;
    EXPECT_NE(ref::cacheKey(s, s.camera, moreSamples), ref::cacheKey(s, s.camera, base)) << "minSpp";
}

// Output of a shell command (stdout), and whether it exited with status 0.
std::string shell(const std::string& command, bool* ok = nullptr)
{
    std::string out;
    FILE* p = popen(command.c_str(), "r");
    if (!p) return out;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    const int status = pclose(p);
    if (ok) *ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    return out;
}

// A change of the path tracer's code must not reuse old entries, without anyone bumping a version by hand:
// the key includes sourceHash(), and sourceHash() is the hash of the sources as they are now (if CMake had
// not hashed them again after an edit, this would fail).
TEST(Cache, KeyFollowsThePathTracersCode)
{
    const core::Scene s = boxRoom(true);
    const ref::RenderSettings rs = settings(ref::LightPaths::Direct, 8, 4);
    EXPECT_EQ(ref::cacheKey(s, s.camera, rs), ref::cacheKey(s, s.camera, rs, ref::sourceHash()));
    EXPECT_NE(ref::cacheKey(s, s.camera, rs, "code A"), ref::cacheKey(s, s.camera, rs, "code B"));

    const std::vector<std::string> files = ref::sourceFiles();
    for (const char* f : {"ref/integrator.cpp", "ref/lights.cpp", "ref/render.cpp", "core/brdf.cpp",
                          "core/sampling.cpp", "core/scene.cpp"})
        EXPECT_NE(std::find(files.begin(), files.end(), f), files.end()) << f << " is not in the code hash";
    std::string command = std::string("cd '") + BOUNCE_SOURCE_ROOT + "' && sha256sum";
    for (const std::string& f : files) command += " '" + f + "'";
    bool ok = false;
    const std::string now = shell(command + " | sha256sum", &ok);
    ASSERT_TRUE(ok) << command;
    EXPECT_EQ(now.substr(0, 64), ref::sourceHash())
        << "the code hash is not that of the sources on disk: CMake did not hash them again after an edit";
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

std::string readBytes(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void writeBytes(const fs::path& p, const std::string& bytes)
{
    std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

// One small entry, rendered once per test; every damaged copy must come back as a miss with this image.
struct Entry {
    TempDir dir;
    core::Scene scene = boxRoom(true);
    ref::RenderSettings rs = settings(ref::LightPaths::Direct, 8, 2);
    std::string key = ref::cacheKey(scene, scene.camera, rs);
    fs::path exr = dir.path / (key + ".exr"), json = dir.path / (key + ".json");
    core::Image image;
    std::string exrBytes, jsonBytes;

    Entry()
    {
        image = lookUp().image;
        exrBytes = readBytes(exr);
        jsonBytes = readBytes(json);
    }
    ref::RenderResult lookUp() const { return ref::cachedReference(scene, scene.camera, rs, dir.path.string()); }
    // Puts the damaged file in place, looks the entry up, and restores the intact entry.
    ref::RenderResult lookUpWith(const fs::path& file, const std::string& bytes) const
    {
        writeBytes(file, bytes);
        const ref::RenderResult r = lookUp();
        writeBytes(exr, exrBytes);
        writeBytes(json, jsonBytes);
        return r;
    }
};

TEST(Cache, TruncatedEntryIsRenderedAgain)
{
    const Entry e;
    for (const fs::path& file : {e.exr, e.json}) {
        const std::string bytes = readBytes(file);
        // Down to the last byte that matters: the JSON's closing brace, not the newline after it.
        const std::size_t last = bytes.find_last_not_of(" \n");
        for (std::size_t length : {std::size_t(0), std::size_t(1), bytes.size() / 2, last}) {
            const ref::RenderResult r = e.lookUpWith(file, bytes.substr(0, length));
            EXPECT_FALSE(r.fromCache) << file.filename() << " cut to " << length << " bytes was trusted";
            EXPECT_EQ(r.image.rgb, e.image.rgb);
        }
    }
    EXPECT_TRUE(e.lookUp().fromCache);
}

// Every single-bit flip anywhere in the EXR (pixels, compressed data, header attributes, even the ones a
// reader ignores) and an edited figure in the JSON make a miss: the entry is checked, never trusted.
TEST(Cache, FlippedBytesAreNeverTrusted)
{
    const Entry e;
    for (std::size_t i = 0; i < e.exrBytes.size(); ++i) {
        std::string damaged = e.exrBytes;
        damaged[i] = char(damaged[i] ^ 1);
        const ref::RenderResult r = e.lookUpWith(e.exr, damaged);
        ASSERT_FALSE(r.fromCache) << "EXR with bit 0 of byte " << i << " flipped was trusted";
        ASSERT_EQ(r.image.rgb, e.image.rgb);
    }
    // A figure of the record: "spp": 2 becomes 3, still valid JSON.
    std::string json = e.jsonBytes;
    const std::size_t spp = json.find("\"spp\": 2");
    ASSERT_NE(spp, std::string::npos) << json;
    json[spp + 7] = '3';
    const ref::RenderResult r = e.lookUpWith(e.json, json);
    EXPECT_FALSE(r.fromCache) << "a sidecar with an edited spp was trusted";
    EXPECT_EQ(r.spp, 2);
}

// Files of two different renders under one key (one writer's EXR with another's sidecar) are not an entry.
TEST(Cache, AnotherValidImageUnderTheKeyIsNotTrusted)
{
    const Entry e;
    core::Image other = e.image;
    other.rgb[0] += 1.0f;
    core::writeExr(e.exr.string(), other);
    const ref::RenderResult r = e.lookUp();
    EXPECT_FALSE(r.fromCache);
    EXPECT_EQ(r.image.rgb, e.image.rgb);
}

// Only one entry's two files are in dir, no temporary of any writer; returns the entry's key.
std::string expectOnlyOneEntry(const fs::path& dir)
{
    std::vector<std::string> names;
    for (const fs::directory_entry& f : fs::directory_iterator(dir)) names.push_back(f.path().filename().string());
    std::sort(names.begin(), names.end());
    const std::string key = fs::path(names.empty() ? "" : names.front()).stem().string();
    EXPECT_EQ(names, (std::vector<std::string>{key + ".exr", key + ".json"}));
    return key;
}

// Threads of one process filling the same entry at once: each writes its own temporaries, every one gets
// the image, and one intact entry is left.
TEST(Cache, ConcurrentWritersLeaveOneIntactEntry)
{
    const core::Scene s = boxRoom(true);
    ref::RenderSettings rs = settings(ref::LightPaths::Direct, 8, 2);
    rs.threads = 1;
    const core::Image expected = ref::render(s, s.camera, rs).image;
    for (int round = 0; round < 5; ++round) {
        const TempDir dir;
        constexpr int kWriters = 4;
        std::atomic<int> ready{0};
        std::vector<std::string> errors(kWriters);
        std::vector<ref::RenderResult> results(kWriters);
        std::vector<std::thread> writers;
        for (int w = 0; w < kWriters; ++w)
            writers.emplace_back([&, w] {
                for (++ready; ready < kWriters;) std::this_thread::yield(); // start together
                try {
                    results[std::size_t(w)] = ref::cachedReference(s, s.camera, rs, dir.path.string());
                } catch (const std::exception& ex) {
                    errors[std::size_t(w)] = ex.what();
                }
            });
        for (std::thread& t : writers) t.join();
        for (int w = 0; w < kWriters; ++w) {
            EXPECT_EQ(errors[std::size_t(w)], "") << "writer " << w << " of round " << round;
            EXPECT_EQ(results[std::size_t(w)].image.rgb, expected.rgb) << "writer " << w << " of round " << round;
        }
        EXPECT_EQ(expectOnlyOneEntry(dir.path), ref::cacheKey(s, s.camera, rs));
        const ref::RenderResult again = ref::cachedReference(s, s.camera, rs, dir.path.string());
        EXPECT_TRUE(again.fromCache) << "round " << round;
        EXPECT_EQ(again.image.rgb, expected.rgb);
    }
}

// Two `bounce reference` processes (as two bench runs) filling the same entry at once: both succeed with
// the same image, and a third run finds one intact entry.
TEST(Cache, TwoProcessesWritingOneEntry)
{
    const TempDir dir;
    const std::string cache = (dir.path / "cache").string();
    auto command = [&](int i) {
        return std::string(BOUNCE_BINARY) + " reference --scene cornell-spot --paths direct --size 16x16 --spp 4" +
               " --threads 1 --cache-dir " + cache + " --out " +
               (dir.path / ("r" + std::to_string(i) + ".exr")).string() + " 2>&1";
    };
    FILE* first = popen(command(1).c_str(), "r");
    FILE* second = popen(command(2).c_str(), "r");
    ASSERT_TRUE(first && second);
    std::string outputs[2];
    int status[2];
    FILE* pipes[2] = {first, second};
    for (int i = 0; i < 2; ++i) {
        char buf[4096];
        while (std::fgets(buf, sizeof buf, pipes[i])) outputs[i] += buf;
        status[i] = pclose(pipes[i]);
    }
    for (int i = 0; i < 2; ++i) EXPECT_TRUE(WIFEXITED(status[i]) && WEXITSTATUS(status[i]) == 0) << outputs[i];
    EXPECT_EQ(readBytes(dir.path / "r1.exr"), readBytes(dir.path / "r2.exr"));
    bool ok = false;
    const std::string third = shell(command(3), &ok);
    EXPECT_TRUE(ok) << third;
    EXPECT_NE(third.find("from cache"), std::string::npos) << third;
    EXPECT_EQ(third.find("damaged"), std::string::npos) << third;
    EXPECT_EQ(readBytes(dir.path / "r3.exr"), readBytes(dir.path / "r1.exr"));
    expectOnlyOneEntry(cache);
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
