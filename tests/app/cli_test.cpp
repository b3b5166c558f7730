// The `bounce` executable end to end: help, listing, bad input (exit status 2, a message saying what is
// allowed, nothing written), a render that writes EXR + PNG + JSON, and the demo under Xvfb.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/cornell.h"
#include "core/gltf_io.h"
#include "core/image.h"
#include "core/metrics.h"
#include "tests/app/image_figures.h"
#include "tests/app/run_command.h"
#include "tests/app/test_backend.h"
#include "tests/core/gltf_bad_cases.h"

namespace {

namespace fs = std::filesystem;
using bounce::testing::testBackend;

using bounce::testing::CommandRun;
using bounce::testing::runShell;

CommandRun run(const std::string& args, const std::string& prefix = "")
{
    return bounce::testing::runBounce(args, prefix);
}

bool commandExists(const std::string& name)
{
    return std::system(("command -v " + name + " >/dev/null 2>&1").c_str()) == 0;
}

fs::path outDir(const std::string& name)
{
    const fs::path d = fs::path(BOUNCE_TEST_OUT) / "cli" / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

bool emptyDir(const fs::path& d)
{
    return fs::is_empty(d);
}

TEST(Cli, HelpEverywhere)
{
    for (const char* cmd : {"--help", "render --help", "list --help", "demo --help", "reference --help",
                            "compare --help", "bench --help", "probe --help"}) {
        const CommandRun r = run(cmd);
        EXPECT_EQ(r.status, 0) << cmd << "\n" << r.output;
        EXPECT_NE(r.output.find("usage"), std::string::npos) << cmd;
    }
}

TEST(Cli, ListShowsScenesTechniquesAndParameters)
{
    const CommandRun r = run("list");
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char* s : {"cornell-area", "cornell-spot", "cornell-point", "direct", "shadow.size", "default"})
        EXPECT_NE(r.output.find(s), std::string::npos) << s;
}

// Each bad input: exit 2, a message naming the problem, nothing written into the output folder.
TEST(Cli, BadInputExitsTwoAndWritesNothing)
{
    const fs::path d = outDir("bad");
    const std::string out = " --backend " + testBackend() + " --out " + (d / "x.exr").string();
    const struct {
        std::string args, says;
    } cases[] = {
        {"render --bogus 1" + out, "unknown option"},
        {"render --size 12x" + out, "--size"},
        {"render --size 0x10" + out, "--size"},
        {"render --technique nosuch" + out, "unknown technique"},
        {"render --set nokey=1" + out, "unknown parameter"},
        {"render --set shadow.size=3" + out, "out of range"},
        {"render --set shadow.pcf=1.5" + out, "integer"},
        {"render --set shadow.linear=maybe" + out, "bool"},
        {"render --technique isr --set rsmSize=100" + out, "power of two"},
        {"render --frames -1" + out, "--frames"},
        {"render --scene /nonexistent/scene.gltf" + out, "scene.gltf"},
        {"render --scene nosuchscene" + out, "nosuchscene"},
        {"render --backend vulkan --out " + (d / "x.exr").string(), "egl"},
        {"render --out " + (d / "x.jpg").string(), ".exr or .png"},
        {"nosuchcommand", "unknown command"},
        {"reference --scene cornell-spot --paths twobounce --spp 4" + out, "onebounce-novis"},
        {"reference --scene cornell-spot --spp 0" + out, "--spp"},
        {"reference --scene cornell-spot --noise 2 --out " + (d / "r.exr").string(), "--noise"},
        {"compare " + (d / "none-a.exr").string() + " " + (d / "none-b.exr").string(), "none-a.exr"},
        {"bench --config /nonexistent/bench.json --out " + (d / "bench").string(), "bench.json"},
    };
    for (const auto& c : cases) {
        const CommandRun r = run(c.args);
        EXPECT_EQ(r.status, 2) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << "\n" << r.output;
        EXPECT_TRUE(emptyDir(d)) << c.args << " left files behind";
    }
}

// The files of a folder, recursively, with their sizes: what a run must leave untouched.
std::map<std::string, std::uintmax_t> listing(const fs::path& d)
{
    std::map<std::string, std::uintmax_t> files;
    for (const auto& e : fs::recursive_directory_iterator(d))
        files[e.path().string()] = e.is_regular_file() ? e.file_size() : 0;
    return files;
}

// The generated set of malformed glTF/GLB files (tests/core/gltf_bad_cases.h) through `bounce render` and
// `bounce reference` (lights and cameras): a refused file exits with status 2 (never a signal, never 1) and a message naming
// the file and the problem, and nothing is written, neither in the output folder nor beside the scene;
// an allowed one renders and writes its three files.
TEST(Cli, MalformedGltfExitsTwoWithTheMessageAndLeavesNothing)
{
    const fs::path root = outDir("malformed");
    for (const bounce::core::test::BadGltfCase& c : bounce::core::test::badGltfCases()) {
        const fs::path scene = root / c.name / "scene", out = root / c.name / "out";
        fs::create_directories(scene);
        fs::create_directories(out);
        const std::string file = c.write(scene);
        const auto before = listing(scene);
        const std::string common = " --scene '" + file + "' --size 16x16 --out '";
        const CommandRun r =
            run("render" + common + (out / "x.exr").string() + "' --frames 1 --warmup 0 --backend " + testBackend());
        if (c.words.empty()) {
            EXPECT_EQ(r.status, 0) << c.name << "\n" << r.output;
            EXPECT_TRUE(fs::exists(out / "x.exr") && fs::exists(out / "x.png") && fs::exists(out / "x.json")) << c.name;
            continue;
        }
        // The path tracer reads lights and cameras too (the loader is shared; one process start each).
        const bool traced =
            c.name.rfind("light", 0) == 0 || c.name.rfind("spot", 0) == 0 || c.name.rfind("camera", 0) == 0;
        const CommandRun ref = !traced ? r
                                       : run("reference" + common + (out / "r.exr").string() +
                                             "' --spp 1 --cache-dir '" + (root / "cache").string() + "'");
        for (const CommandRun* x : {&r, &ref}) {
            const std::string command = x == &r ? "render" : "reference";
            EXPECT_EQ(x->status, 2) << c.name << " (" << command << ")\n" << x->output;
            EXPECT_NE(x->output.find(c.words), std::string::npos) << c.name << " (" << command << ")\n" << x->output;
            EXPECT_NE(x->output.find(fs::path(file).filename().string()), std::string::npos) << c.name;
        }
        EXPECT_TRUE(emptyDir(out)) << c.name << " left files behind";
        EXPECT_EQ(listing(scene), before) << c.name << " changed the scene's folder";
    }
}

TEST(Cli, RenderWritesExrPngAndJsonRecord)
{
    const fs::path d = outDir("render");
    const CommandRun r = run("render --scene cornell-spot --size 48x32 --frames 2 --warmup 1 --backend " +
                             testBackend() + " --out " + (d / "spot.png").string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("GL renderer"), std::string::npos);
    ASSERT_TRUE(fs::exists(d / "spot.exr"));
    ASSERT_TRUE(fs::exists(d / "spot.png"));
    ASSERT_TRUE(fs::exists(d / "spot.json"));
    const bounce::core::Image img = bounce::core::readImage((d / "spot.exr").string());
    EXPECT_EQ(img.width, 48);
    EXPECT_EQ(img.height, 32);
    std::ifstream in(d / "spot.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["technique"], "direct");
    EXPECT_EQ(j["backend"], testBackend());
    EXPECT_FALSE(j["renderer"].get<std::string>().empty());
    EXPECT_GE(j["passes"].size(), 3u);
    for (const auto& p : j["passes"]) EXPECT_EQ(p["frames"], 2);
    EXPECT_GT(j["bytesAllocatedTotal"].get<double>(), 0.0);
    EXPECT_TRUE(j["bytesAllocated"].contains("gbuffer.geometry"));
    // No temporary files survive.
    for (const auto& e : fs::directory_iterator(d))
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

// `bounce probe` measures the ceilings and caches them per renderer; a render then gives every pass with a
// declared cost its bound and efficiency in the record. Figures are only checked for being positive and
// finite: their size is the machine's, not a property of the code.
TEST(Cli, ProbeCachesCeilingsAndRenderRecordsBounds)
{
    const fs::path d = outDir("probe");
    const std::string env = "env BOUNCE_CACHE=" + (d / "cache").string() + " ";
    const CommandRun bad = run("probe --size 5 --backend " + testBackend(), env);
    EXPECT_EQ(bad.status, 2) << bad.output;
    const CommandRun probe =
        run("probe --size 64 --repeats 1 --backend " + testBackend() + " --json " + (d / "c.json").string(), env);
    ASSERT_EQ(probe.status, 0) << probe.output;
    std::ifstream cin(d / "c.json");
    const nlohmann::json c = nlohmann::json::parse(cin);
    for (const char* key : {"fragmentGflops", "computeGflops", "fragmentGBps", "computeImageGBps", "computeBufferGBps",
                            "fragmentGfetches", "computeGfetches", "fragmentGuniformWords", "computeGuniformWords",
                            "mtrianglesPerSecond"})
        EXPECT_GT(c[key].get<double>(), 0.0) << key;
    bool cached = false;
    for (const auto& e : fs::directory_iterator(d / "cache"))
        cached |= e.path().filename().string().rfind("probe-", 0) == 0;
    ASSERT_TRUE(cached) << "the measured ceilings are cached under the renderer";
    const CommandRun render = run("render --scene cornell-spot --size 32x32 --frames 1 --warmup 0 --backend " +
                                      testBackend() + " --out " + (d / "r.exr").string(),
                                  env);
    ASSERT_EQ(render.status, 0) << render.output;
    std::ifstream rin(d / "r.json");
    const nlohmann::json j = nlohmann::json::parse(rin);
    bool anyBound = false;
    for (const auto& p : j["passes"]) {
        EXPECT_TRUE(p.contains("costDeclared")) << p["pass"];
        if (p.contains("boundMs")) {
            anyBound = true;
            EXPECT_GT(p["boundMs"].get<double>(), 0.0) << p["pass"];
            EXPECT_TRUE(std::isfinite(p["efficiency"].get<double>())) << p["pass"];
        }
    }
    EXPECT_TRUE(anyBound) << render.output;
    // Without cached ceilings the record has the work but no bounds.
    fs::remove_all(d / "cache");
    const CommandRun plain = run("render --scene cornell-spot --size 32x32 --frames 1 --warmup 0 --backend " +
                                     testBackend() + " --out " + (d / "p.exr").string(),
                                 env);
    ASSERT_EQ(plain.status, 0) << plain.output;
    std::ifstream pin(d / "p.json");
    // Named: a range-for over a member of the temporary parse() returns reads freed memory.
    const nlohmann::json plainRecord = nlohmann::json::parse(pin);
    for (const auto& p : plainRecord["passes"]) EXPECT_FALSE(p.contains("boundMs")) << p["pass"];
}

// `bounce reference`: the image and its record, rendered and then served from the cache.
TEST(Cli, ReferenceWritesImageAndRecordThenHitsTheCache)
{
    const fs::path d = outDir("reference");
    const std::string args =
        "reference --scene cornell-spot --paths direct --size 24x16 --spp 8 --threads 2 --cache-dir " +
        (d / "cache").string() + " --out " + (d / "ref.exr").string() + " --json " + (d / "ref.json").string();
    const CommandRun first = run(args);
    ASSERT_EQ(first.status, 0) << first.output;
    EXPECT_NE(first.output.find("rays/s"), std::string::npos) << first.output;
    const bounce::core::Image img = bounce::core::readImage((d / "ref.exr").string());
    EXPECT_EQ(img.width, 24);
    EXPECT_EQ(img.height, 16);
    std::ifstream in(d / "ref.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["paths"], "direct");
    EXPECT_EQ(j["spp"], 8);
    EXPECT_FALSE(j["fromCache"].get<bool>());
    EXPECT_GT(j["raysPerSecond"].get<double>(), 0.0);
    const CommandRun second = run(args);
    ASSERT_EQ(second.status, 0) << second.output;
    std::ifstream in2(d / "ref.json");
    EXPECT_TRUE(nlohmann::json::parse(in2)["fromCache"].get<bool>()) << second.output;
    const bounce::core::Image again = bounce::core::readImage((d / "ref.exr").string());
    EXPECT_EQ(again.rgb, img.rgb) << "the cached image differs from the rendered one";
}

// `bounce compare`: figures for images of one size (zero for an image against itself, the closed form
// for a constant offset), a clear refusal for images of different sizes.
TEST(Cli, CompareReportsFiguresAndRefusesDifferentSizes)
{
    const fs::path d = outDir("compare");
    bounce::core::Image a(8, 6), b(8, 6), c(6, 8);
    for (float& v : a.rgb) v = 1.0f;
    for (float& v : b.rgb) v = 1.5f;
    bounce::core::writeImage((d / "a.exr").string(), a);
    bounce::core::writeImage((d / "b.exr").string(), b);
    bounce::core::writeImage((d / "c.exr").string(), c);
    const CommandRun same = run("compare " + (d / "a.exr").string() + " " + (d / "b.exr").string() + " --json " +
                                (d / "ab.json").string() + " --heatmap " + (d / "ab.png").string());
    ASSERT_EQ(same.status, 0) << same.output;
    EXPECT_TRUE(fs::exists(d / "ab.png"));
    std::ifstream in(d / "ab.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_NEAR(j["rmse"].get<double>(), 0.5, 1e-6) << j.dump();
    EXPECT_NEAR(j["relativeRmse"].get<double>(), 0.5 / 1.5, 1e-6) << j.dump();
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(j["channelMeanImage"][c].get<double>(), 1.0, 1e-6) << j.dump();
        EXPECT_NEAR(j["channelMeanReference"][c].get<double>(), 1.5, 1e-6) << j.dump();
    }
    const fs::path before = d / "ac.json";
    const CommandRun different =
        run("compare " + (d / "a.exr").string() + " " + (d / "c.exr").string() + " --json " + before.string());
    EXPECT_EQ(different.status, 2) << different.output;
    EXPECT_NE(different.output.find("8x6"), std::string::npos) << different.output;
    EXPECT_NE(different.output.find("6x8"), std::string::npos) << different.output;
    EXPECT_FALSE(fs::exists(before)) << "a refused comparison wrote its record";
}

// --block compares block means (a checkerboard against its flat mean: every pixel off, every 2x2 block
// exact), an image twice the reference's size is box-filtered to it first, and --mask-above leaves out the
// blocks that hold or touch a bright pixel of the reference (the one wrong block sits beside it).
TEST(Cli, CompareByBlocksWithTheEmitterMasked)
{
    const fs::path d = outDir("compare-blocks");
    bounce::core::Image checker(8, 8), flat(8, 8), fine(16, 16);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            checker.set(x, y, glm::vec3((x + y) % 2 ? 1.0f : 0.0f));
            flat.set(x, y, glm::vec3(0.5f));
        }
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) fine.set(x, y, glm::vec3(0.5f));
    bounce::core::writeImage((d / "checker.exr").string(), checker);
    bounce::core::writeImage((d / "flat.exr").string(), flat);
    bounce::core::writeImage((d / "fine.exr").string(), fine);
    const auto figure = [&](const std::string& args, const char* key) {
        const fs::path json = d / "c.json";
        const CommandRun r = run("compare " + args + " --json " + json.string());
        EXPECT_EQ(r.status, 0) << r.output;
        return nlohmann::json::parse(std::ifstream(json))[key].get<double>();
    };
    const std::string checkerVsFlat = (d / "checker.exr").string() + " " + (d / "flat.exr").string();
    EXPECT_NEAR(figure(checkerVsFlat, "relativeRmse"), 1.0, 1e-6);
    EXPECT_NEAR(figure(checkerVsFlat + " --block 2", "relativeRmse"), 0.0, 1e-6);
    EXPECT_NEAR(figure((d / "fine.exr").string() + " " + (d / "flat.exr").string(), "relativeRmse"), 0.0, 1e-6);
    // A bright reference pixel at (0, 0) and a wrong one at (2, 0): with 2x2 blocks the wrong one's block
    // touches the bright one's and is masked with it, then nothing else differs.
    bounce::core::Image bright = flat, wrong = flat;
    bright.set(0, 0, glm::vec3(20.0f));
    wrong.set(0, 0, glm::vec3(20.0f));
    wrong.set(2, 0, glm::vec3(3.0f));
    bounce::core::writeImage((d / "bright.exr").string(), bright);
    bounce::core::writeImage((d / "wrong.exr").string(), wrong);
    const std::string wrongVsBright = (d / "wrong.exr").string() + " " + (d / "bright.exr").string();
    EXPECT_GT(figure(wrongVsBright + " --block 2", "relativeRmse"), 0.1);
    EXPECT_NEAR(figure(wrongVsBright + " --block 2 --mask-above 1", "relativeRmse"), 0.0, 1e-6);
    EXPECT_EQ(figure(wrongVsBright + " --block 2 --mask-above 1", "maskedBlocks"), 4.0); // (0,0) and its 3 neighbours
    EXPECT_EQ(run("compare " + checkerVsFlat + " --block 3").status, 2) << "3 does not divide 8";
}

// A CSV file as rows of name -> text.
std::vector<std::map<std::string, std::string>> readCsv(const fs::path& file)
{
    std::ifstream in(file);
    std::string line;
    std::vector<std::string> names;
    std::vector<std::map<std::string, std::string>> rows;
    while (std::getline(in, line)) {
        std::vector<std::string> fields(1);
        bool quoted = false;
        for (char c : line) {
            if (c == '"')
                quoted = !quoted;
            else if (c == ',' && !quoted)
                fields.emplace_back();
            else
                fields.back().push_back(c);
        }
        if (names.empty()) {
            names = fields;
            continue;
        }
        std::map<std::string, std::string> row;
        for (std::size_t i = 0; i < names.size() && i < fields.size(); ++i) row[names[i]] = fields[i];
        rows.push_back(row);
    }
    return rows;
}

// Pixels whose centre sees cornell-area's emitter: camera rays through the pixel centres against the light
// quad's triangles (Moeller-Trumbore; nothing stands between the camera and the ceiling's light).
std::vector<bool> emitterPixels(const bounce::core::Scene& scene, int w, int h)
{
    std::vector<bool> hit(std::size_t(w) * h, false);
    for (const bounce::core::Mesh& m : scene.meshes) {
        if (!scene.materials[m.material].isEmissive()) continue;
        for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]),
                c(m.positions[m.indices[t + 2]]);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const glm::dvec3 o(scene.camera.position),
                        d(scene.camera.rayDirection(float(x) + 0.5f, float(y) + 0.5f, w, h));
                    const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
                    const double det = glm::dot(e1, p);
                    if (std::abs(det) < 1e-12) continue;
                    const glm::dvec3 s = o - a, q = glm::cross(s, e1);
                    const double u = glm::dot(s, p) / det, v = glm::dot(d, q) / det, dist = glm::dot(e2, q) / det;
                    if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && dist > 0.0) hit[std::size_t(y) * w + x] = true;
                }
        }
    }
    return hit;
}

// The emitter pixels and their eight neighbours set to black, as the bench's error figures leave them out.
bounce::core::Image withoutEmitters(bounce::core::Image image, const std::vector<bool>& emitters)
{
    const int w = image.width, h = image.height;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool near = false;
            for (int j = std::max(y - 1, 0); j <= std::min(y + 1, h - 1); ++j)
                for (int i = std::max(x - 1, 0); i <= std::min(x + 1, w - 1); ++i) near = near || emitters[j * w + i];
            if (near) image.set(x, y, glm::vec3(0.0f));
        }
    return image;
}

using bounce::testing::relativeRmseOf;

// `bounce bench` on a tiny config: the four files, one row per scene x run, and the figures in them. Each
// error is computed again here from the same references (`bounce reference` with the bench's settings:
// served from the same cache) and the same renders (`bounce render`: deterministic), with the emitter mask
// made independently (camera rays against the light quad): rel_rmse_own and rel_rmse_full agree to 1e-4
// relative, and each technique is closer to its own light paths than to `full`. The Pareto front the plot marks
// (printed by the plot script) is the set of rows no other row beats in both time and error.
// A progressive run with "curve": true records its error after every timed frame (steps, directions and
// GPU time growing) and the bench plots those curves beside the path tracer's rows in convergence.png.
// The same run's report.html is then opened in headless Chromium (tests/app/report_browser.mjs: no
// console error or failed request, one plot point per row, flipping changes the pixels, the error map of
// an image against itself is zero, the viewer's tone mapping is the PNG writer's); a viewport that is not
// a power of two (24x20) beside the 16x16 ones. A camera-path run's player is checked there too (steps,
// play and pause show its frames beside their references).
TEST(Cli, BenchPlotsCurvesAndWritesAReportThatABrowserOpens)
{
    const fs::path d = outDir("bench-curve");
    const fs::path config = d / "curve.json";
    std::ofstream(d / "path.json") << R"({"frames": 3, "keys": [
        {"frame": 0, "camera": "0.278,0.273,-0.8:0.278,0.273,0.2795:39.3"},
        {"frame": 2, "camera": "0.3,0.273,-0.8:0.278,0.273,0.2795:39.3"}]})";
    std::ofstream(config) << R"({"size": "16x16", "warmup": 0, "frames": 3, "reference": {"spp": 64},
                                "scenes": ["cornell-spot"], "pathTracerSpp": [4, 16],
                                "runs": [{"technique": "grb", "curve": true,
                                          "set": {"directionsPerFrame": 2, "kbufferSize": 32, "atlasTexels": 1024}},
                                         {"technique": "direct", "size": "24x20", "frames": 1},
                                         {"technique": "direct", "path": ")"
                          << (d / "path.json").string() << R"(", "every": 2}]})";
    const CommandRun r = run("bench --backend " + testBackend() + " --config " + config.string() + " --out " +
                             (d / "out").string() + " --cache " + (d / "cache").string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_GT(fs::file_size(d / "out" / "convergence.png"), 1000u) << r.output;
    std::ifstream in(d / "out" / "results.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    int curves = 0, tracer = 0;
    for (const nlohmann::json& rec : j) {
        if (rec.value("technique", "") == "path-tracer") ++tracer;
        if (!rec.contains("curve")) continue;
        ++curves;
        const nlohmann::json& c = rec["curve"];
        ASSERT_EQ(c.size(), 3u);
        for (std::size_t i = 0; i < c.size(); ++i) {
            EXPECT_EQ(c[i]["accumulated"].get<int>(), 2 * int(i + 1));
            EXPECT_GT(c[i]["relativeRmseFull"].get<double>(), 0.0);
            if (i > 0) {
                EXPECT_GT(c[i]["elapsedMs"].get<double>(), c[i - 1]["elapsedMs"].get<double>());
            }
        }
    }
    EXPECT_EQ(curves, 1);
    EXPECT_EQ(tracer, 2);
    for (const nlohmann::json& rec : j) {
        const std::string image = rec.value("image", "");
        EXPECT_TRUE(fs::exists(d / "out" / (image + ".exr"))) << "row image " << image;
        const nlohmann::json references = rec.value("references", nlohmann::json::object());
        // A camera-path row's reference is its last measured frame's, of its own light paths.
        EXPECT_TRUE(references.contains(rec.contains("sequence") ? rec.at("lightPaths").get<std::string>() : "full"))
            << image;
        for (const auto& [paths, id] : references.items())
            EXPECT_TRUE(fs::exists(d / "out" / (id.get<std::string>() + ".js"))) << paths << " reference " << id;
    }

    // What the browser does with the page needs node and Chromium (scripts/install-deps.sh, .ci/run installs
    // both); a GPU machine that runs the suites from scripts/device-check.sh has neither.
    if (!commandExists("node")) GTEST_SKIP() << "node is not installed (scripts/install-deps.sh installs it)";
    const CommandRun browser =
        runShell("node " + (fs::path(BOUNCE_SOURCE_ROOT) / "tests/app/report_browser.mjs").string() + " " +
                 (d / "out").string());
    EXPECT_EQ(browser.status, 0) << browser.output;
}

TEST(Cli, BenchWritesTheFourFilesWithTheirFigures)
{
    const fs::path d = outDir("bench");
    const fs::path config = d / "tiny.json";
    std::ofstream(config) << R"({"size": "16x16", "warmup": 0, "frames": 1, "reference": {"spp": 64},
                                "scenes": ["cornell-area"],
                                "runs": [{"technique": "direct"}, {"technique": "rsm", "sweep": {"vpls": [4, 64]}}]})";
    const std::string cache = " --cache-dir " + (d / "cache").string();
    const CommandRun r = run("bench --backend " + testBackend() + " --config " + config.string() + " --out " +
                             (d / "out").string() + " --cache " + (d / "cache").string());
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char* f : {"results.csv", "results.json", "report.md", "speed_error.png"})
        EXPECT_TRUE(fs::exists(d / "out" / f)) << f << "\n" << r.output;
    const auto rows = readCsv(d / "out" / "results.csv");
    ASSERT_EQ(rows.size(), 3u) << "one row per scene x setting";
    std::ifstream md(d / "out" / "report.md");
    const std::string report((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_NE(report.find("## cornell-area"), std::string::npos);

    const bounce::core::Scene area = bounce::core::makeCornell("cornell-area");
    const std::vector<bool> emitters = emitterPixels(area, 16, 16);
    ASSERT_GT(std::count(emitters.begin(), emitters.end(), true), 0) << "cornell-area's light is in view";
    std::map<std::string, bounce::core::Image> references;
    for (const char* paths : {"direct", "onebounce-novis", "full"}) {
        const fs::path file = d / (std::string("ref-") + paths + ".exr");
        const CommandRun ref = run(std::string("reference --scene cornell-area --size 16x16 --spp 64 --paths ") +
                                   paths + cache + " --out " + file.string());
        ASSERT_EQ(ref.status, 0) << ref.output;
        EXPECT_NE(ref.output.find("cache"), std::string::npos) << "the bench's own reference: " << ref.output;
        references[paths] = withoutEmitters(bounce::core::readImage(file.string()), emitters);
    }
    for (const auto& row : rows) {
        if (row.at("scene") != "cornell-area") continue;
        const std::string technique = row.at("technique"), params = row.at("params");
        const fs::path file = d / ("render-" + technique + std::to_string(&row - &rows[0]) + ".exr");
        const std::string set = params == "defaults" ? "" : " --set " + params;
        const CommandRun render = run("render --backend " + testBackend() +
                                      " --scene cornell-area --size 16x16 --frames 1 --warmup 0 "
                                      "--technique " +
                                      technique + set + " --out " + file.string());
        ASSERT_EQ(render.status, 0) << render.output;
        const bounce::core::Image image = withoutEmitters(bounce::core::readImage(file.string()), emitters);
        const double own = relativeRmseOf(image, references.at(row.at("light_paths")));
        const double full = relativeRmseOf(image, references.at("full"));
        EXPECT_NEAR(std::stod(row.at("rel_rmse_own")), own, 1e-4 * own) << technique << " " << params;
        EXPECT_NEAR(std::stod(row.at("rel_rmse_full")), full, 1e-4 * full) << technique << " " << params;
        std::printf("[ measured ] %s (%s): relative RMSE %.4g against its own light paths, %.4g against full\n",
                    technique.c_str(), params.c_str(), own, full);
        // Closer to its own light paths than to `full`, which adds what it leaves out (measured at this
        // size: direct 0.56 against 0.71, rsm 0.50 / 0.46 against 0.58 / 0.53; a 16x16 image with a
        // 64-spp reference is mostly edges and noise).
        EXPECT_LT(own, full) << technique << " " << params;
    }

    // The Pareto front of each panel: the rows no other row beats in both the time of the image and the error,
    // found here from the CSV's figures alone; the plot script prints what it marks (the bench's pareto_own and
    // pareto_full), and report.md's table lists the same rows.
    for (const std::string scene : {"cornell-area"})
        for (const std::string column : {"rel_rmse_own", "rel_rmse_full"}) {
            std::vector<std::string> front;
            for (const auto& a : rows) {
                if (a.at("scene") != scene) continue;
                const double ta = std::stod(a.at("image_ms")), ea = std::stod(a.at(column));
                bool dominated = false;
                for (const auto& b : rows) {
                    if (&a == &b || b.at("scene") != scene) continue;
                    const double tb = std::stod(b.at("image_ms")), eb = std::stod(b.at(column));
                    dominated = dominated || (tb <= ta && eb <= ea && (tb < ta || eb < ea));
                }
                if (!dominated) front.push_back(a.at("technique") + " (" + a.at("params") + ")");
            }
            const std::string prefix = "pareto front, " + scene + " 16x16, " + column + ": ";
            const auto at = r.output.find(prefix);
            ASSERT_NE(at, std::string::npos) << prefix << "\n" << r.output;
            const std::string printed =
                r.output.substr(at + prefix.size(), r.output.find('\n', at) - at - prefix.size());
            ASSERT_FALSE(front.empty());
            for (const std::string& f : front)
                EXPECT_NE(printed.find(f + " "), std::string::npos) << f << " in " << printed;
            EXPECT_EQ(std::count(printed.begin(), printed.end(), ';') + 1, std::ptrdiff_t(front.size())) << printed;
            // report.md's front (time of the image, one frame each here, against `full`): the same rows.
            if (column != "rel_rmse_full") continue;
            const std::size_t section = report.find("### Pareto front", report.find("## " + scene));
            ASSERT_NE(section, std::string::npos) << report;
            const std::string table =
                report.substr(section, report.find("\n\n", report.find("|---", section)) - section);
            EXPECT_EQ(std::count(table.begin(), table.end(), '\n') - 3, std::ptrdiff_t(front.size())) << table;
            for (const std::string& f : front) {
                const std::string technique = f.substr(0, f.find(" (")), params = f.substr(f.find(" (") + 2);
                EXPECT_NE(table.find("| " + technique + " | " + params.substr(0, params.size() - 1) + " |"),
                          std::string::npos)
                    << f << " in " << table;
            }
        }
}

// A bench config is checked whole before anything runs: the wrong shape, unknown keys, wrong types, values
// out of range, unknown scenes, techniques and parameters (against their declarations), and an empty
// sweep each exit with status 2 and a message naming the key, and nothing is written (not even --out).
TEST(Cli, BenchConfigIsCheckedBeforeAnythingRuns)
{
    const fs::path d = outDir("bench-config");
    const std::string direct = R"("runs": [{"technique": "direct"}])";
    const struct {
        std::string config, key, says;
    } cases[] = {
        {"[]", "the file", "must be an object"},
        {"{}", "runs", "missing"},
        {R"({"runs": []})", "runs", "non-empty list"},
        {R"({"runs": {"technique": "direct"}})", "runs", "non-empty list"},
        {R"({"runs": [42]})", "runs[0]", "must be an object"},
        {"{" + direct + R"(, "frame": 3})", "frame", "unknown key"},
        {R"({"runs": [{"technique": "direct", "sett": {}}]})", "runs[0].sett", "unknown key"},
        {R"({"runs": [{"set": {}}]})", "runs[0].technique", "missing"},
        {R"({"runs": [{"technique": "nosuch"}]})", "runs[0].technique", "nosuch"},
        {R"({"runs": [{"technique": 7}]})", "runs[0].technique", "must be a string"},
        {R"({"runs": [{"technique": "rsm", "set": {"vpls": 0}}]})", "runs[0].set.vpls", "range"},
        {R"({"runs": [{"technique": "rsm", "set": {"nokey": 1}}]})", "runs[0].set.nokey", "unknown parameter"},
        {R"({"runs": [{"technique": "rsm", "set": {"vpls": [1]}}]})", "runs[0].set.vpls",
         "number, a boolean or a string"},
        {R"({"runs": [{"technique": "direct", "set": {"shadow.size": 3}}]})", "runs[0].set.shadow.size", "range"},
        // The references see the scene's normal maps: a run without them would be judged against them.
        {R"({"runs": [{"technique": "direct", "set": {"normalMaps": 0}}]})", "runs[0].set.normalMaps",
         "normalTexture\": false"},
        {R"({"runs": [{"technique": "rsm", "sweep": {"vpls": []}}]})", "runs[0].sweep.vpls", "non-empty list"},
        {R"({"runs": [{"technique": "rsm", "sweep": {}}]})", "runs[0].sweep", "non-empty object"},
        {R"({"runs": [{"technique": "rsm", "sweep": {"vpls": [16, -3]}}]})", "runs[0].sweep.vpls", "range"},
        {R"({"runs": [{"technique": "isr", "sweep": {"multires": ["maybe"]}}]})", "runs[0].sweep.multires", "bool"},
        {R"({"runs": [{"technique": "direct", "against": {"technique": "rsm", "set": {"vpls": "many"}}}]})",
         "runs[0].against.set.vpls", "vpls"},
        {R"({"runs": [{"technique": "direct", "temporalFrames": 1}]})", "runs[0].temporalFrames", "at least 2"},
        {R"({"runs": [{"technique": "direct", "frames": 0}]})", "runs[0].frames", "[1, "},
        {R"({"runs": [{"technique": "direct", "scenes": ["cornell-area"]}]})", "runs[0].scenes", "cornell-area"},
        {"{" + direct + R"(, "frames": "5"})", "frames", "whole number"},
        {"{" + direct + R"(, "warmup": -1})", "warmup", "[0, "},
        {"{" + direct + R"(, "size": "12"})", "size", "WxH"},
        {"{" + direct + R"(, "scenes": "cornell-spot"})", "scenes", "non-empty list"},
        {"{" + direct + R"(, "scenes": ["nosuch"]})", "scenes[0]", "nosuch"},
        {"{" + direct + R"(, "reference": {"spp": -1}})", "reference.spp", "[1, "},
        {"{" + direct + R"(, "reference": {"sp": 4}})", "reference.sp", "unknown key"},
        {"{" + direct + R"(, "reference": {"noise": 5}})", "reference.noise", "(0, 1)"},
        {"{" + direct + R"(, "reference": {"size": "7x7"}})", "reference.size", "does not divide"},
        {"{" + direct + R"(, "size": "64x48", "reference": {"size": "16x16"}})", "reference.size", "aspect ratio"},
        {"{" + direct + R"(, "compareTo": ["twobounce"]})", "compareTo[0]", "twobounce"},
        {"{" + direct + R"(, "rays": 1.5})", "rays", "whole number"},
        // Camera-path runs: the file read and checked, the still run's keys refused with it.
        {R"({"runs": [{"technique": "direct", "path": "/nonexistent/walk.json"}]})", "runs[0].path", "walk.json"},
        {R"({"runs": [{"technique": "direct", "path": "walk.json", "frames": 3}]})", "runs[0].frames",
         "cannot be given with \"path\""},
        {R"({"runs": [{"technique": "direct", "every": 3}]})", "runs[0].every", "camera-path run"},
        {R"({"runs": [{"technique": "direct", "indirectScale": 0, "path": ")" + std::string(BOUNCE_SOURCE_ROOT) +
             R"(/bench/paths/cornell-orbit.json"}]})",
         "runs[0].indirectScale", "[1, 16]"},
    };
    int i = 0;
    for (const auto& c : cases) {
        const fs::path config = d / ("config" + std::to_string(i++) + ".json");
        std::ofstream(config) << c.config;
        const fs::path out = d / "out";
        const CommandRun r = run("bench --backend " + testBackend() + " --config " + config.string() + " --out " +
                                 out.string() + " --cache " + (d / "cache").string());
        EXPECT_EQ(r.status, 2) << c.config << "\n" << r.output;
        EXPECT_NE(r.output.find("bench config: " + c.key + ": "), std::string::npos) << c.config << "\n" << r.output;
        EXPECT_NE(r.output.find(c.says), std::string::npos) << c.config << "\n" << r.output;
        EXPECT_FALSE(fs::exists(out)) << c.config << ": wrote " << out;
        EXPECT_FALSE(fs::exists(d / "cache")) << c.config << ": wrote the cache";
    }
}

// "rays" in a bench config adds the GPU-against-Embree table: both kinds of rays per scene, the same
// triangles found by both, positive rates.
TEST(Cli, BenchReportsRayCastingAgainstEmbree)
{
    const fs::path d = outDir("bench-rays");
    const fs::path config = d / "rays.json";
    std::ofstream(config) << R"({"size": "8x8", "warmup": 0, "frames": 1, "reference": {"spp": 1}, "rays": 1024,
                                "scenes": ["cornell-area"], "runs": [{"technique": "direct"}]})";
    const CommandRun r = run("bench --backend " + testBackend() + " --config " + config.string() + " --out " +
                             (d / "out").string() + " --cache " + (d / "cache").string());
    ASSERT_EQ(r.status, 0) << r.output;
    std::ifstream in(d / "out" / "rays.json");
    ASSERT_TRUE(in) << r.output;
    const nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_EQ(j.size(), 1u);
    EXPECT_EQ(j[0]["scene"], "cornell-area");
    for (const char* kind : {"coherent", "incoherent"}) {
        SCOPED_TRACE(kind);
        const nlohmann::json& f = j[0][kind];
        EXPECT_EQ(f["rays"], 1024);
        EXPECT_GT(f["embreeRaysPerS"].get<double>(), 0.0);
        EXPECT_GT(f["gpuComputeRaysPerS"].get<double>(), 0.0);
        EXPECT_GT(f["gpuFragmentRaysPerS"].get<double>(), 0.0);
        EXPECT_GE(f["sameTriangle"].get<double>(), 0.99);
    }
    std::ifstream md(d / "out" / "report.md");
    const std::string report((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_NE(report.find("GPU ray casting against Embree"), std::string::npos);
}

// A glTF file given by path renders like the built-in scene it was written from.
TEST(Cli, RenderAGltfByPath)
{
    const fs::path d = outDir("gltf");
    const std::string asset = std::string(BOUNCE_SOURCE_ROOT) + "/assets/cornell-spot.gltf";
    const CommandRun a = run("render --scene " + asset + " --size 32x32 --frames 1 --warmup 0 --backend " +
                             testBackend() + " --out " + (d / "a.exr").string());
    ASSERT_EQ(a.status, 0) << a.output;
    const CommandRun b = run("render --scene cornell-spot --size 32x32 --frames 1 --warmup 0 --backend " +
                             testBackend() + " --out " + (d / "b.exr").string());
    ASSERT_EQ(b.status, 0) << b.output;
    const auto ia = bounce::core::readImage((d / "a.exr").string()),
               ib = bounce::core::readImage((d / "b.exr").string());
    ASSERT_EQ(ia.rgb.size(), ib.rgb.size());
    for (std::size_t i = 0; i < ia.rgb.size(); ++i) EXPECT_NEAR(ia.rgb[i], ib.rgb[i], 1e-5f + 1e-5f * ib.rgb[i]) << i;
}

// The demo checks its --script before the window opens: with no display at all (so that opening a window
// would fail with another message), each bad script exits 2 with a message naming the step.
TEST(Cli, DemoScriptIsCheckedBeforeTheWindowOpens)
{
    const struct {
        std::string script, says;
    } cases[] = {
        {"wait:1,technique:nosuch", "unknown technique 'nosuch'"},
        {"compare:nosuch,quit", "unknown technique 'nosuch'"},
        {"technique:isr,set:nokey=1", "unknown parameter 'nokey'"},
        {"set:rsmSize=64", "unknown parameter 'rsmSize'"}, // direct has no rsmSize
        {"set:shadow.size=3", "out of range"},
        {"set:shadow.linear=maybe", "bool"},
        {"wait:soon", "wait"},
        {"fly:1", "unknown step"},
    };
    for (const auto& c : cases) {
        const CommandRun r = run("demo --scene cornell-spot --size 32x32 --script '" + c.script + "'",
                                 "env -u DISPLAY -u WAYLAND_DISPLAY ");
        EXPECT_EQ(r.status, 2) << c.script << "\n" << r.output;
        EXPECT_NE(r.output.find(c.says), std::string::npos) << c.script << "\n" << r.output;
        EXPECT_NE(r.output.find("--script"), std::string::npos) << c.script << "\n" << r.output;
        EXPECT_EQ(r.output.find("GL renderer"), std::string::npos) << "a context was created: " << r.output;
    }
}

// The demo takes --camera and --light as render does, and refuses bad ones before any window opens.
TEST(Cli, DemoChecksCameraAndLightBeforeTheWindowOpens)
{
    for (const std::string& bad : {std::string("--light 'bogus:x=1'"), std::string("--camera 1,2,3")}) {
        const CommandRun r = run("demo --scene cornell-spot --size 32x32 " + bad, "env -u DISPLAY -u WAYLAND_DISPLAY ");
        EXPECT_EQ(r.status, 2) << bad << "\n" << r.output;
        EXPECT_EQ(r.output.find("GL renderer"), std::string::npos) << "a context was created: " << r.output;
    }
}

// The demo in a real window (Xvfb in CI): a few frames, switches through the techniques of the image-space
// radiosity family (with a parameter set from the script, as a widget would) and a side-by-side
// comparison (with a frame parameter set while comparing), and a screenshot that must be the Cornell box: not black, the red wall on the left, the
// green wall on the right, and brighter than direct light alone (the indirect light is there).
TEST(Cli, DemoRunsSwitchesTechniqueAndShowsTheCornellBox)
{
    if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no DISPLAY: the suite runs under xvfb-run in CI (test.sh)";
    const fs::path d = outDir("demo");
    const fs::path shot = d / "shot.exr", direct = d / "direct.exr";
    const CommandRun r = run("demo --scene cornell-area --size 160x120 --script wait:2,screenshot:" + direct.string() +
                             ",technique:multires-gather,set:vpls=64,wait:1,technique:isr,set:rsmSize=64,wait:1,"
                             "technique:hisr,set:rsmSize=64,wait:1,technique:rsm,set:vpls=64,wait:2,screenshot:" +
                             shot.string() + ",compare:isr,wait:1,set:shadow.pcf=2,wait:1,quit");
    ASSERT_EQ(r.status, 0) << r.output;
    ASSERT_TRUE(fs::exists(shot)) << r.output;
    ASSERT_TRUE(fs::exists(d / "shot.png"));
    const auto total = [](const bounce::core::Image& i) {
        double s = 0.0;
        for (float v : i.rgb) s += v;
        return s;
    };
    const bounce::core::Image img = bounce::core::readImage(shot.string());
    const bounce::core::Image directImg = bounce::core::readImage(direct.string());
    EXPECT_GT(total(img) / double(img.rgb.size()), 1.05 * total(directImg) / double(directImg.rgb.size()))
        << "rsm adds no indirect light to direct";
    double sum = 0.0;
    glm::vec3 left(0.0f), right(0.0f);
    for (int y = img.height / 3; y < 2 * img.height / 3; ++y)
        for (int x = 0; x < img.width; ++x) {
            const glm::vec3 v = img.at(x, y);
            sum += v.x + v.y + v.z;
            if (x < img.width / 4) left += v;
            if (x >= img.width - img.width / 4) right += v;
        }
    EXPECT_GT(sum, 0.0) << "black screenshot";
    EXPECT_GT(left.x, 2.0f * left.y) << "the left wall should be red";
    EXPECT_GT(right.y, 2.0f * right.x) << "the right wall should be green";
}

// The frame budget: while the camera moves and frames take longer than the budget (1 ms here, so any
// machine is over it), indirect light drops to a coarser resolution, and once the camera has been still it
// comes back to full resolution; the screenshot after that is the full-resolution image of the same view
// (a renderer at full resolution throughout gives the same picture).
TEST(Cli, DemoFrameBudgetCoarsensWhileMovingAndReturnsWhenStill)
{
    if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no DISPLAY: the suite runs under xvfb-run in CI (test.sh)";
    const fs::path d = outDir("demo-budget");
    const std::string moved = (d / "moved.exr").string(), still = (d / "still.exr").string();
    const std::string log = (d / "frames.csv").string();
    const CommandRun r = run("demo --scene cornell-spot --size 96x64 --technique rsm --frame-log " + log +
                             " --script set:vpls=16,budget:1,move:4,screenshot:" + moved +
                             ",move:3,wait:60,screenshot:" + still + ",quit");
    ASSERT_EQ(r.status, 0) << r.output;
    const auto coarse = r.output.find("budget: indirect light at 1/2 resolution (48x32) while moving");
    ASSERT_NE(coarse, std::string::npos) << r.output;
    EXPECT_NE(r.output.find("budget: indirect light at 1/4 resolution (24x16)"), std::string::npos) << r.output;
    const auto full = r.output.find("budget: full resolution (still)", coarse);
    ASSERT_NE(full, std::string::npos) << "never back to full resolution:\n" << r.output;
    const bounce::core::Image a = bounce::core::readImage(moved), b = bounce::core::readImage(still);
    EXPECT_EQ(a.width, 96);
    EXPECT_EQ(b.width, 96);
    // The frame log: a row per frame, moving frames at a coarser scale, the last ones still at full
    // resolution, and the passes of each frame.
    std::ifstream in(log);
    std::string line;
    ASSERT_TRUE(std::getline(in, line));
    EXPECT_EQ(line, "seconds,frame_ms,render_ms,indirect_scale,direct_samples,moving,technique,passes");
    int rows = 0, coarseMoving = 0;
    std::string last;
    while (std::getline(in, line)) {
        ++rows;
        last = line;
        if (line.find(",1,1,rsm,") != std::string::npos && line.find(",1,1,1,rsm,") == std::string::npos)
            ++coarseMoving;
    }
    EXPECT_GE(rows, 60) << "the moves run during the waits: 60 frames at least";
    EXPECT_GT(coarseMoving, 0) << "no moving frame at a coarser scale";
    EXPECT_NE(last.find(",1,1,0,rsm,"), std::string::npos)
        << "the last frame is not still at full resolution: " << last;
    EXPECT_NE(last.find("gather="), std::string::npos) << last;
}

// The frame budget's other direction: moving frames far under a budget of 100 s take 2, 4, then 8 points
// of the direct light (the frame log's direct_samples, what the frame renders), unless the command line
// sets moving.directSamples, which then stays as set.
TEST(Cli, DemoFrameBudgetAddsDirectPointsWhereMovingFramesHaveRoom)
{
    if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no DISPLAY: the suite runs under xvfb-run in CI (test.sh)";
    const fs::path d = outDir("demo-budget-points");
    const auto pointsLogged = [&](const std::string& sets) {
        const std::string log = (d / "frames.csv").string();
        const CommandRun r = run("demo --scene cornell-spot --size 48x32 --technique direct " + sets + " --frame-log " +
                                 log + " --script budget:100000,move:8,wait:8,quit");
        EXPECT_EQ(r.status, 0) << r.output;
        std::ifstream in(log);
        std::string line;
        std::getline(in, line);
        std::set<std::string> moving; // direct_samples of the moving frames
        while (std::getline(in, line)) {
            std::vector<std::string> f;
            std::stringstream row(line);
            for (std::string c; std::getline(row, c, ',') && f.size() < 6;) f.push_back(c);
            if (f.size() == 6 && f[5] == "1") moving.insert(f[4]);
        }
        return std::pair{moving, r.output};
    };
    const auto [added, out] = pointsLogged("");
    EXPECT_EQ(added, (std::set<std::string>{"2", "4", "8"})) << "the first moving frame takes two already\n" << out;
    EXPECT_NE(out.find("budget: 8 points of the direct light per moving frame"), std::string::npos) << out;
    const auto [kept, keptOut] = pointsLogged("--set moving.directSamples=2");
    EXPECT_EQ(kept, std::set<std::string>{"2"}) << keptOut;
}

// A frame parameter set while comparing rebuilds both halves: with the same technique on both sides the
// two halves are the same image before and after, and the change shows (a 16-texel shadow map against
// 1024: relative RMSE about 1 on cornell-spot at 64x64). Each screenshot while comparing writes the
// right half too and prints the relative RMSE of the right against the left, which must be the figure
// of the two images written.
TEST(Cli, DemoFrameParameterRebuildsBothSidesOfAComparison)
{
    if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no DISPLAY: the suite runs under xvfb-run in CI (test.sh)";
    const fs::path d = outDir("demo-frame");
    const auto file = [&](const char* name) { return (d / name).string(); };
    const CommandRun r =
        run("demo --scene cornell-spot --size 128x64 --script wait:1,compare:direct,wait:1,screenshot:" +
            file("before.exr") + ",set:shadow.size=16,wait:1,screenshot:" + file("after.exr") +
            ",compare:rsm,wait:1,screenshot:" + file("mixed.exr") + ",quit");
    ASSERT_EQ(r.status, 0) << r.output;
    using bounce::core::readImage;
    using bounce::core::relativeRmse;
    const auto before = readImage(file("before.exr")), beforeRight = readImage(file("before-right.exr"));
    const auto after = readImage(file("after.exr")), afterRight = readImage(file("after-right.exr"));
    ASSERT_EQ(before.width, 64) << "each half is half the window";
    ASSERT_EQ(beforeRight.width, 64);
    EXPECT_LT(relativeRmse(beforeRight, before), 1e-5) << "the same technique differs between the halves";
    EXPECT_GT(relativeRmse(after, before), 0.1) << "shadow.size=16 changed nothing on the left";
    EXPECT_LT(relativeRmse(afterRight, after), 1e-5) << "the right half was not rebuilt with shadow.size=16";
    const auto mixed = readImage(file("mixed.exr")), mixedRight = readImage(file("mixed-right.exr"));
    const std::string says = "relative RMSE of rsm (right) against direct (left): ";
    const auto at = r.output.find(says);
    ASSERT_NE(at, std::string::npos) << r.output;
    const double printed = std::stod(r.output.substr(at + says.size()));
    const double expected = relativeRmse(mixedRight, mixed);
    EXPECT_GT(expected, 0.01) << "rsm adds indirect light that direct lacks";
    EXPECT_NEAR(printed, expected, 1e-4 * expected) << r.output;
}

} // namespace

namespace {

// `bounce list --json` is the whole registry for scripts: every technique with its light paths, passes,
// G-buffer reads and typed parameters, the frame's passes and parameters.
TEST(Cli, ListJsonIsTheWholeRegistry)
{
    const CommandRun r = run("list --json");
    ASSERT_EQ(r.status, 0) << r.output;
    const nlohmann::json j = nlohmann::json::parse(r.output);
    ASSERT_TRUE(j["techniques"].is_array());
    bool sawRsm = false;
    for (const auto& t : j["techniques"]) {
        for (const char* key :
             {"name", "paper", "lightPaths", "summary", "passes", "reads", "parameters", "progressive"})
            EXPECT_TRUE(t.contains(key)) << t["name"] << " lacks " << key;
        EXPECT_NE(std::find(j["lightPaths"].begin(), j["lightPaths"].end(), t["lightPaths"]), j["lightPaths"].end());
        for (const auto& p : t["parameters"]) {
            for (const char* key : {"name", "type", "default", "meaning", "update"}) EXPECT_TRUE(p.contains(key));
            if (p["type"] == "int" || p["type"] == "float") {
                EXPECT_TRUE(p.contains("min") && p.contains("max"));
            }
        }
        if (t["name"] == "rsm") {
            sawRsm = true;
            EXPECT_EQ(t["lightPaths"], "onebounce-novis");
            EXPECT_EQ(t["passes"][0]["name"], "rsm");
        }
    }
    EXPECT_TRUE(sawRsm);
    // shadow, gbuffer, direct, composite, accumulate, direct.samples, temporal, edge-aa.lines, edge-aa
    EXPECT_EQ(j["frame"]["passes"].size(), 9u);
}

// --reference puts the error against a reference in the record; one whose size does not divide the
// render's is refused before anything is written.
TEST(Cli, RenderReferenceGivesTheErrorInTheRecord)
{
    const fs::path d = outDir("reference-error");
    ASSERT_EQ(run("render --backend " + testBackend() +
                  " --technique direct --size 16x16 --frames 1 --warmup 0 --out " + (d / "ref.exr").string())
                  .status,
              0);
    const CommandRun same = run("render --backend " + testBackend() +
                                " --technique direct --size 16x16 --frames 1 --warmup 0 --reference " +
                                (d / "ref.exr").string() + " --out " + (d / "same.exr").string());
    ASSERT_EQ(same.status, 0) << same.output;
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(d / "same.json"))["relativeRmse"].get<double>(), 0.0)
        << "the same deterministic render";

    // Another technique at twice the size: the record's figure is the error of its image, box-downsampled
    // to the reference's size, as computed here from the written files.
    const CommandRun other =
        run("render --backend " + testBackend() + " --technique rsm --size 32x32 --frames 1 --warmup 0 --reference " +
            (d / "ref.exr").string() + " --out " + (d / "rsm.exr").string());
    ASSERT_EQ(other.status, 0) << other.output;
    const double recorded = nlohmann::json::parse(std::ifstream(d / "rsm.json"))["relativeRmse"].get<double>();
    const double expected = bounce::core::relativeRmse(
        bounce::core::boxDownsample(bounce::core::readImage((d / "rsm.exr").string()), 16, 16),
        bounce::core::readImage((d / "ref.exr").string()));
    EXPECT_GT(expected, 0.01) << "rsm adds indirect light to direct";
    EXPECT_NEAR(recorded, expected, 1e-6 * expected);

    const fs::path bad = outDir("reference-error-bad");
    const CommandRun r = run("render --backend " + testBackend() + " --technique direct --size 30x30 --reference " +
                             (d / "ref.exr").string() + " --out " + (bad / "x.exr").string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("must divide"), std::string::npos) << r.output;
    EXPECT_TRUE(emptyDir(bad));
}

} // namespace

namespace {

// A NaN image compares as infinitely wrong, never as perfect, and `compare` exits with status 1 after
// writing its figures.
TEST(Cli, CompareOfANanImageFails)
{
    const fs::path d = outDir("compare-nan");
    bounce::core::Image ref(4, 4), nan(4, 4);
    for (float& v : ref.rgb) v = 0.5f;
    for (float& v : nan.rgb) v = std::numeric_limits<float>::quiet_NaN();
    bounce::core::writeImage((d / "ref.exr").string(), ref);
    bounce::core::writeImage((d / "nan.exr").string(), nan);
    const CommandRun r = run("compare " + (d / "nan.exr").string() + " " + (d / "ref.exr").string() + " --json " +
                             (d / "c.json").string());
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("NaN/Inf"), std::string::npos) << r.output;
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(d / "c.json"));
    EXPECT_EQ(j["rmse"], "inf");
    EXPECT_EQ(j["ssim"], 0.0);
    EXPECT_EQ(j["nonFiniteImage"], 48);
}

} // namespace

namespace {

// A NaN reference makes the render's error infinite, written as "inf" in its record (JSON has no infinity:
// a plain dump would write null), never 0.
TEST(Cli, RenderAgainstANanReferenceRecordsAnInfiniteError)
{
    const fs::path d = outDir("render-nan-reference");
    bounce::core::Image nan(8, 8);
    for (float& v : nan.rgb) v = std::numeric_limits<float>::quiet_NaN();
    bounce::core::writeImage((d / "nan.exr").string(), nan);
    const CommandRun r =
        run("render --scene cornell-spot --size 16x16 --frames 1 --warmup 0 --backend " + testBackend() +
            " --reference " + (d / "nan.exr").string() + " --out " + (d / "x.exr").string());
    EXPECT_EQ(r.status, 0) << r.output << " (the image itself is finite)";
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(d / "x.json"));
    EXPECT_EQ(j["relativeRmse"], "inf") << j.dump();
    EXPECT_EQ(j["nonFiniteValues"], 0);
}

// A size whose render targets need more than half of the available memory (llvmpipe: the system's) is
// refused before any target is allocated, with status 2, a message naming --size and nothing written.
TEST(Cli, RenderSizeBeyondMemoryIsRefusedUpFront)
{
    std::ifstream meminfo("/proc/meminfo");
    std::string key, unit;
    double kib = 0.0, available = 0.0;
    while (meminfo >> key >> kib >> unit)
        if (key == "MemAvailable:") available = kib * 1024.0;
    // 84 bytes of targets per pixel for cornell-glossy, which needs every G-buffer target (glossy metal, an
    // emitter: gl/frame/frame_budget.cpp, frameTargetBytesPerPixel()); --size stops at 16384.
    const double side = std::ceil(std::sqrt(0.75 * available / 84.0));
    if (available <= 0.0 || side > 16384.0) GTEST_SKIP() << "this machine's memory holds the largest --size";
    const fs::path d = outDir("too-big");
    const std::string size = std::to_string(int(side)) + "x" + std::to_string(int(side));
    const CommandRun r = run("render --scene cornell-glossy --backend " + testBackend() + " --size " + size +
                             " --out " + (d / "x.exr").string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("--size " + size), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("GiB"), std::string::npos) << r.output;
    EXPECT_TRUE(emptyDir(d));
}

// A run writes its EXR, PNG and JSON as a set: when one cannot be written (here the JSON's path is a
// folder) the run is refused before rendering and nothing of the set is left behind.
TEST(Cli, RenderWritesItsFilesAsASet)
{
    const fs::path d = outDir("file-set");
    fs::create_directories(d / "record.json"); // a folder where the JSON should go
    const CommandRun r = run("render --backend " + testBackend() + " --size 8x8 --frames 1 --warmup 0 --out " +
                             (d / "img.exr").string() + " --json " + (d / "record.json").string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_FALSE(fs::exists(d / "img.exr"));
    EXPECT_FALSE(fs::exists(d / "img.png"));
    for (const auto& e : fs::directory_iterator(d)) EXPECT_EQ(e.path().filename(), "record.json") << e.path();
}

// `reference --cache-dir` pointing at a file is refused before the render starts, and says how to fix it.
TEST(Cli, ReferenceChecksTheCacheFolderFirst)
{
    const fs::path d = outDir("cache-file");
    std::ofstream(d / "not-a-folder") << "x";
    const CommandRun r = run("reference --scene cornell-spot --paths direct --size 8x8 --spp 100000 --out " +
                             (d / "ref.exr").string() + " --cache-dir " + (d / "not-a-folder").string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("--no-cache"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("samples:"), std::string::npos) << "it rendered first";
    EXPECT_FALSE(fs::exists(d / "ref.exr"));
}

} // namespace

namespace {

double imageMean(const bounce::core::Image& im)
{
    double sum = 0.0;
    for (float v : im.rgb) sum += v;
    return sum / double(im.rgb.size());
}

// The cornell-spot glTF without its camera and its light, written by the project's writer.
fs::path cornellWithoutCameraAndLight(const fs::path& dir)
{
    bounce::core::Scene s = bounce::core::makeCornell("cornell-spot");
    s.lights.clear();
    const fs::path file = dir / "bare.gltf";
    bounce::core::writeGltf(s, file.string());
    // The writer always writes the camera: drop it, as most downloaded files have none.
    nlohmann::json j = nlohmann::json::parse(std::ifstream(file));
    j.erase("cameras");
    for (auto& n : j["nodes"]) n.erase("camera");
    std::ofstream(file) << j.dump();
    return file;
}

// A glTF with no camera gets one framing its bounds (the record says so); with no light it warns, and
// --light gives it one.
TEST(Cli, GltfWithoutCameraOrLightRendersWithFramingCameraAndCommandLineLight)
{
    const fs::path d = outDir("bare-gltf");
    const fs::path bare = cornellWithoutCameraAndLight(d);
    const CommandRun dark = run("render --backend " + testBackend() + " --size 16x16 --frames 1 --warmup 0 --scene " +
                                bare.string() + " --out " + (d / "dark.exr").string());
    ASSERT_EQ(dark.status, 0) << dark.output;
    EXPECT_NE(dark.output.find("no light"), std::string::npos) << dark.output;
    EXPECT_NE(dark.output.find("framed the bounds"), std::string::npos) << dark.output;
    const CommandRun lit =
        run("render --backend " + testBackend() + " --size 16x16 --frames 1 --warmup 0 --scene " + bare.string() +
            " --light 'point:position=0.278,0.4,0.279;intensity=1' --out " + (d / "lit.exr").string());
    ASSERT_EQ(lit.status, 0) << lit.output;
    EXPECT_GT(imageMean(bounce::core::readImage((d / "lit.exr").string())), 0.01);
    const nlohmann::json rec = nlohmann::json::parse(std::ifstream(d / "lit.json"));
    EXPECT_EQ(rec["cameraSource"], "framed the bounds (the glTF has no camera)");
}

// The light given on the command line and the same light in the glTF (KHR_lights_punctual, as the built-in
// cornell-spot writes it) give the same image.
TEST(Cli, CommandLineLightEqualsTheSameLightInTheGltf)
{
    const fs::path d = outDir("light-equal");
    const fs::path bare = cornellWithoutCameraAndLight(d);
    const bounce::core::Scene canonical = bounce::core::makeCornell("cornell-spot");
    const bounce::core::Light& l = canonical.lights.at(0);
    char light[512];
    std::snprintf(
        light, sizeof light,
        "spot:position=%.9g,%.9g,%.9g;direction=%.9g,%.9g,%.9g;intensity=%.9g,%.9g,%.9g;outerDeg=%.9g;innerDeg=%.9g",
        l.position.x, l.position.y, l.position.z, l.direction.x, l.direction.y, l.direction.z, l.intensity.x,
        l.intensity.y, l.intensity.z, double(l.outerConeRad) * 180.0 / M_PI, double(l.innerConeRad) * 180.0 / M_PI);
    const bounce::core::Camera& c = canonical.camera;
    char camera[256];
    const glm::vec3 target = c.position + c.forward;
    std::snprintf(camera, sizeof camera, "%.9g,%.9g,%.9g:%.9g,%.9g,%.9g:%.9g", c.position.x, c.position.y, c.position.z,
                  target.x, target.y, target.z, double(c.yfovRad) * 180.0 / M_PI);
    const CommandRun a =
        run("render --backend " + testBackend() + " --size 32x32 --frames 1 --warmup 0 --scene cornell-spot --out " +
            (d / "gltf.exr").string());
    ASSERT_EQ(a.status, 0) << a.output;
    const CommandRun b =
        run("render --backend " + testBackend() + " --size 32x32 --frames 1 --warmup 0 --scene " + bare.string() +
            " --light '" + light + "' --camera '" + camera + "' --out " + (d / "cli.exr").string());
    ASSERT_EQ(b.status, 0) << b.output;
    const auto ia = bounce::core::readImage((d / "gltf.exr").string());
    const auto ib = bounce::core::readImage((d / "cli.exr").string());
    // Degrees and decimal text round trip the cone angles to within a float ulp or two: 1e-4 relative.
    EXPECT_LT(bounce::core::relativeRmse(ib, ia), 1e-4) << light << "\n" << camera;
    EXPECT_GT(imageMean(ia), 0.01);
}

// A setup whose asset is missing exits with status 2 and names the file; nothing is written.
TEST(Cli, SetupWithAMissingAssetExitsTwoNamingTheFile)
{
    const fs::path d = outDir("setup-missing");
    std::ofstream(d / "s.json") << R"({"gltf": "not-here/model.gltf", "lights": []})";
    const CommandRun r = run("render --backend " + testBackend() + " --size 8x8 --scene " + (d / "s.json").string() +
                             " --out " + (d / "out" / "a.exr").string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("not-here/model.gltf"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(d / "out" / "a.exr"));
}

// A setup written here (no benchmark asset needed): a glTF without camera or light, and a setup that gives
// it a spot. It renders lit, without the no-light warning, from the setup's camera.
TEST(Cli, GeneratedSetupWithALightRendersLit)
{
    const fs::path d = outDir("setup-generated");
    cornellWithoutCameraAndLight(d);
    std::ofstream(d / "setup.json") << R"({"gltf": "bare.gltf",
      "camera": {"position": [0.278, 0.273, -0.8], "target": [0.278, 0.273, 0.0], "yfovDeg": 39.3},
      "lights": [{"type": "spot", "position": [0.278, 0.54, 0.279], "direction": [0, -1, 0], "intensity": 1,
                  "outerDeg": 40}]})";
    const CommandRun r = run("render --backend " + testBackend() + " --size 16x16 --frames 1 --warmup 0 --scene " +
                             (d / "setup.json").string() + " --out " + (d / "render.exr").string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.output.find("no light"), std::string::npos) << r.output;
    EXPECT_GT(imageMean(bounce::core::readImage((d / "render.exr").string())), 0.01);
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(d / "render.json"))["cameraSource"], "setup");
}

// Every setup the project ships loads and renders lit when its asset is there (CI has ../shared beside
// the project); a missing asset is reported, not failed, since the assets are not part of the project.
TEST(Cli, ShippedSetupsRenderLit)
{
    const fs::path d = outDir("setups");
    for (const auto& e : fs::directory_iterator(fs::path(BOUNCE_SOURCE_ROOT) / "assets" / "setups")) {
        const CommandRun r = run("render --backend " + testBackend() + " --size 16x16 --frames 1 --warmup 0 --scene " +
                                 e.path().string() + " --out " + (d / e.path().stem()).string() + ".exr");
        if (r.status == 2 && r.output.find("is not there") != std::string::npos) {
            std::printf("[ skipped  ] %s: its asset is not there\n", e.path().filename().c_str());
            continue;
        }
        ASSERT_EQ(r.status, 0) << e.path() << "\n" << r.output;
        EXPECT_EQ(r.output.find("no light"), std::string::npos) << e.path();
        EXPECT_GT(imageMean(bounce::core::readImage((d / e.path().stem()).string() + ".exr")), 1e-3) << e.path();
    }
}

} // namespace

namespace {

// `bounce rays` casts the same rays on the GPU and with Embree: on the Cornell box (no ties that the
// two watertight tests could break differently at this count) they find the same triangles.
TEST(Cli, RaysComparesTheGpuCasterWithEmbree)
{
    const fs::path d = outDir("rays");
    const CommandRun r =
        run("rays --backend " + testBackend() + " --scene cornell-spot --rays 1024 --repeat 1 --threads 1 --json " +
            (d / "rays.json").string());
    ASSERT_EQ(r.status, 0) << r.output;
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(d / "rays.json"));
    for (const char* kind : {"coherent", "incoherent"}) {
        EXPECT_GT(j[kind]["embreeRaysPerS"].get<double>(), 0.0);
        EXPECT_GT(j[kind]["gpuComputeRaysPerS"].get<double>(), 0.0);
        EXPECT_GT(j[kind]["gpuFragmentRaysPerS"].get<double>(), 0.0);
        EXPECT_GE(j[kind]["sameTriangle"].get<double>(), 0.99) << kind;
    }
    EXPECT_EQ(run("rays --rays 0").status, 2);
}

} // namespace
