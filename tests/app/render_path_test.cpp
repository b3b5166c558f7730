// `bounce render --path` end to end (issue 58, "Interface"): the frames written (0, K, 2K, ... and the
// last, %04d), a sequence.json with every frame's GPU ms, and the refusals (a bad path, the still-image
// options) with exit status 2 and nothing written.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/image.h"
#include "tests/app/image_figures.h"
#include "tests/app/run_command.h"
#include "tests/app/test_backend.h"

namespace {

namespace fs = std::filesystem;
using bounce::testing::CommandRun;
using bounce::testing::testBackend;

fs::path outDir(const std::string& name)
{
    const fs::path d = fs::path(BOUNCE_TEST_OUT) / "render-path" / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

fs::path writePath(const fs::path& dir, const std::string& name, const std::string& text)
{
    const fs::path p = dir / name;
    std::ofstream(p) << text;
    return p;
}

const char* const kLastKey = "0.278,0.273,-0.5:0.278,0.273,0.3:39.3";
const char* const kPointLight = "point:position=0.2,0.45,0.3;intensity=0.3";

// A dolly toward the Cornell box's back wall over `frames` frames.
std::string dolly(int frames)
{
    return R"({"frames": )" + std::to_string(frames) + R"(, "keys": [
        {"frame": 0, "camera": "0.278,0.273,-0.8:0.278,0.273,0:39.3"},
        {"frame": )" +
           std::to_string(frames - 1) + R"(, "camera": ")" + kLastKey + R"("}]})";
}

std::set<std::string> filesIn(const fs::path& d)
{
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(d)) names.insert(e.path().filename().string());
    return names;
}

std::string common(const std::string& scene)
{
    return "render --scene " + scene + " --technique direct --size 32x24 --backend " + testBackend() + " ";
}

CommandRun renderPath(const fs::path& path, const fs::path& out, const std::string& extra,
                      const std::string& scene = "cornell-spot")
{
    return bounce::testing::runBounce(
        common(scene) + "--path " + path.string() + " --out " + out.string() + " " + extra, "BOUNCE_PROGRESS=0 ");
}

// One unjittered frame (no warm-up, --frames 1), as a frame of a moving sequence is drawn.
bounce::core::Image still(const std::string& scene, const std::string& extra, const fs::path& out)
{
    const CommandRun r =
        bounce::testing::runBounce(common(scene) + "--frames 1 --warmup 0 --out " + out.string() + " " + extra);
    EXPECT_EQ(r.status, 0) << r.output;
    return bounce::core::readImage(out.string());
}

double meanAbsDifference(const bounce::core::Image& a, const bounce::core::Image& b)
{
    EXPECT_EQ(a.rgb.size(), b.rgb.size());
    double sum = 0.0;
    for (std::size_t i = 0; i < a.rgb.size() && i < b.rgb.size(); ++i) sum += std::abs(a.rgb[i] - b.rgb[i]);
    return sum / double(std::max<std::size_t>(a.rgb.size(), 1));
}

// 7 frames, every 3rd: frames 0, 3 and 6 (the last) as EXR, and a record of all 7 with their GPU time.
// The last frame is the one a still render makes at the last key's camera, and far from the first's view.
TEST(RenderPath, WritesEveryKthFrameAndARecordOfEveryFrame)
{
    const fs::path d = outDir("every3");
    const fs::path path = writePath(d, "dolly.json", dolly(7));
    const fs::path out = d / "seq";
    const CommandRun r = renderPath(path, out, "--every 3");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(filesIn(out),
              (std::set<std::string>{"frame-0000.exr", "frame-0003.exr", "frame-0006.exr", "sequence.json"}));
    for (const char* name : {"frame-0000.exr", "frame-0003.exr", "frame-0006.exr"}) {
        const bounce::core::Image img = bounce::core::readImage((out / name).string());
        EXPECT_EQ(img.width, 32) << name;
        EXPECT_EQ(img.height, 24) << name;
        double sum = 0.0;
        for (float v : img.rgb) {
            ASSERT_TRUE(std::isfinite(v)) << name;
            sum += v;
        }
        EXPECT_GT(sum, 0.0) << name << " is black";
    }
    const bounce::core::Image first = bounce::core::readImage((out / "frame-0000.exr").string()),
                              last = bounce::core::readImage((out / "frame-0006.exr").string()),
                              atLastKey = still("cornell-spot", std::string("--camera ") + kLastKey, d / "still.exr");
    // Both are one unjittered frame at one camera: equal but for rounding (llvmpipe here: 0 measured).
    EXPECT_LT(meanAbsDifference(last, atLastKey), 1e-3 * meanAbsDifference(first, atLastKey));

    std::ifstream in(out / "sequence.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    ASSERT_EQ(j["frames"].size(), 7u);
    for (int i = 0; i < 7; ++i) {
        EXPECT_EQ(j["frames"][i]["index"], i);
        const double ms = j["frames"][i]["ms"].get<double>();
        EXPECT_TRUE(std::isfinite(ms) && ms > 0.0) << "frame " << i << ": " << ms;
    }
    EXPECT_EQ(j["every"], 3);
    EXPECT_EQ(j["frameCount"], 7);
    EXPECT_EQ(j["indirectScale"], 1);
    EXPECT_EQ(j["technique"], "direct");
    EXPECT_EQ(j["width"], 32);
    EXPECT_EQ(j["height"], 24);
    EXPECT_EQ(j["path"], path.string());
}

// The last frame is written even where K does not reach it: 7 frames, every 5th -> 0, 5 and 6. A lights
// entry at frame 3 replaces the scene's punctual lights (cornell-area has none: its light is an emitter):
// frame 6 is the still render with that light, frame 0 the one without.
TEST(RenderPath, WritesTheLastFrameTooAndChangesLightsAtTheirFrame)
{
    const fs::path d = outDir("every5");
    const fs::path out = d / "seq";
    const fs::path path = writePath(d, "lights.json",
                                    R"({"frames": 7, "keys": [{"frame": 0, "camera": ")" + std::string(kLastKey) +
                                        R"("}], "lights": [{"frame": 3, "light": [")" + kPointLight + R"("]}]})");
    // accumulate=0: the frames whose camera and lights hold are not averaged, so that frame 6 is one frame.
    const std::string flags = "--set accumulate=0 --indirect-scale 2";
    const CommandRun r = renderPath(path, out, "--every 5 " + flags, "cornell-area");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(filesIn(out),
              (std::set<std::string>{"frame-0000.exr", "frame-0005.exr", "frame-0006.exr", "sequence.json"}));
    std::ifstream in(out / "sequence.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["frames"].size(), 7u);
    EXPECT_EQ(j["indirectScale"], 2);
    const std::string camera = std::string(" --camera ") + kLastKey;
    const bounce::core::Image first = bounce::core::readImage((out / "frame-0000.exr").string()),
                              last = bounce::core::readImage((out / "frame-0006.exr").string()),
                              lit = still("cornell-area", flags + camera + " --light '" + kPointLight + "'",
                                          d / "lit.exr"),
                              unlit = still("cornell-area", flags + camera, d / "unlit.exr");
    EXPECT_LT(meanAbsDifference(last, lit), 1e-3 * meanAbsDifference(last, unlit));
    EXPECT_LT(meanAbsDifference(first, unlit), 1e-3 * meanAbsDifference(first, lit));
}

// Each bad path or option: exit 2, a message naming the problem, and nothing written (the output folder is
// not even made).
TEST(RenderPath, RefusesBadPathsAndStillOptionsWritingNothing)
{
    const fs::path d = outDir("bad");
    const fs::path good = writePath(d, "good.json", dolly(4));
    const struct {
        std::string path, extra, says;
    } cases[] = {
        {writePath(d, "nan.json",
                   R"({"frames": 4, "keys": [{"frame": 0, "camera": "nan,0.273,-0.8:0.278,0.273,0:39"}]})")
             .string(),
         "", "not finite"},
        {writePath(d, "inf.json",
                   R"({"frames": 4, "keys": [{"frame": 0, "camera": "0.278,0.273,-0.8:0.278,inf,0:39"}]})")
             .string(),
         "", "not finite"},
        {writePath(d, "zero.json",
                   R"({"frames": 4, "keys": [{"frame": 0, "camera": "0.278,0.273,0:0.278,0.273,0:39"}]})")
             .string(),
         "", "zero-length view"},
        // Keys that are fine, whose frame 1 (t = 1/4) has its position on its target.
        {writePath(d, "zero-between.json", R"({"frames": 5, "keys": [{"frame": 0, "camera": "0,0.25,0:0,0.25,0.5:39"},
                                                                    {"frame": 4, "camera": "0,0.25,1:0,0.25,-0.5:39"}]})")
             .string(),
         "", "frame 1: the position equals the target"},
        {writePath(d, "order.json", R"({"frames": 9, "keys": [{"frame": 4, "camera": "0,0.3,-1:0,0.3,0:39"},
                                                              {"frame": 2, "camera": "0,0.3,-2:0,0.3,0:39"}]})")
             .string(),
         "", "strictly increase"},
        {(d / "missing.json").string(), "", "cannot open"},
        {good.string(), "--frames 3", "--frames cannot be given with --path"},
        {good.string(), "--warmup 0", "--warmup cannot be given with --path"},
        {good.string(), "--camera 0,0,0:0,0,1", "--camera cannot be given with --path"},
        {good.string(), "--light 'point:position=0,1,0;intensity=1'", "--light cannot be given with --path"},
        {good.string(), "--every 0", "--every must be in [1, 100000]"},
        {good.string(), "--indirect-scale 17", "--indirect-scale must be in [1, 16]"},
    };
    for (const auto& c : cases) {
        const fs::path out = d / "seq";
        fs::remove_all(out);
        const CommandRun r = renderPath(c.path, out, c.extra);
        EXPECT_EQ(r.status, 2) << c.path << " " << c.extra << "\n" << r.output;
        EXPECT_NE(r.output.find(c.says), std::string::npos) << c.path << " " << c.extra << "\n" << r.output;
        EXPECT_FALSE(fs::exists(out)) << c.path << " " << c.extra;
    }
    // With --path, --out is a folder; without it, --every has no meaning.
    const CommandRun file = renderPath(good, d / "x.exr", "");
    EXPECT_EQ(file.status, 2) << file.output;
    EXPECT_NE(file.output.find("--out is a folder"), std::string::npos) << file.output;
    const CommandRun every = bounce::testing::runBounce("render --size 8x8 --every 2 --out " + (d / "y.exr").string());
    EXPECT_EQ(every.status, 2) << every.output;
    EXPECT_NE(every.output.find("--every needs --path"), std::string::npos) << every.output;
    EXPECT_FALSE(fs::exists(d / "x.exr"));
    EXPECT_FALSE(fs::exists(d / "y.exr"));
}

} // namespace

namespace {

using bounce::testing::relativeRmseOf;

// The flicker as the issue defines it: the RMS of the change of the error image over the references' mean.
double flickerOf(const bounce::core::Image& a, const bounce::core::Image& ra, const bounce::core::Image& b,
                 const bounce::core::Image& rb)
{
    double se = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        const double change = (double(b.rgb[i]) - rb.rgb[i]) - (double(a.rgb[i]) - ra.rgb[i]);
        se += change * change;
        sum += 0.5 * (double(ra.rgb[i]) + rb.rgb[i]);
    }
    return std::sqrt(se / double(a.rgb.size())) / (sum / double(a.rgb.size()));
}

} // namespace

// `bounce bench` with a "path" run (issue 58, "Sequences"), its figures computed again here by other
// commands: each measured frame (iK and iK+1, K = 2, so all 4 here) is the frame `bounce render --path`
// writes, compared with `bounce reference` at that frame's camera; the row's error is their mean; the
// flicker is that of the pairs (0, 1) and (2, 3) only, from the formula above, the second half's that of
// (2, 3); with "stillFrames" 2,
// frames 0 and 2 are also rendered still (`bounce render --camera C --warmup 0 --frames 2`), and the
// second half's ratio is that of the mean of frames 2 and 3 to frame 2's still error. cornell-spot shows
// no emitter, so no pixel is masked. A key at every frame gives cameras the command line can name exactly.
TEST(RenderPath, BenchPathRunMeasuresEachFrameAgainstItsOwnReference)
{
    const fs::path d = outDir("bench");
    const std::vector<std::string> cameras = {
        "0.278,0.273,-0.8:0.278,0.273,0.2795:39.3", "0.288,0.273,-0.8:0.278,0.273,0.2795:39.3",
        "0.298,0.28,-0.8:0.278,0.273,0.2795:39.3", "0.308,0.29,-0.79:0.278,0.273,0.2795:39.3"};
    std::string keys;
    for (std::size_t f = 0; f < cameras.size(); ++f)
        keys += std::string(f ? ", " : "") + R"({"frame": )" + std::to_string(f) + R"(, "camera": ")" + cameras[f] +
                R"("})";
    const fs::path path = writePath(d, "path.json", R"({"frames": 4, "keys": [)" + keys + "]}");
    std::ofstream(d / "config.json") << R"({"size": "16x16", "reference": {"spp": 64}, "scenes": ["cornell-spot"],
        "runs": [{"technique": "direct", "path": ")"
                                     << path.string() << R"(", "every": 2, "stillFrames": 2}]})";
    const std::string cache = (d / "cache").string();
    const CommandRun bench =
        bounce::testing::runBounce("bench --backend " + testBackend() + " --config " + (d / "config.json").string() +
                                   " --out " + (d / "out").string() + " --cache " + cache);
    ASSERT_EQ(bench.status, 0) << bench.output;
    std::ifstream in(d / "out" / "results.json");
    const nlohmann::json rec = nlohmann::json::parse(in).at(0);
    const nlohmann::json& q = rec.at("sequence");
    ASSERT_EQ(q.at("frames").size(), 4u);

    const CommandRun frames =
        bounce::testing::runBounce("render --scene cornell-spot --technique direct --size 16x16 --backend " +
                                       testBackend() + " --path " + path.string() + " --out " + (d / "frames").string(),
                                   "BOUNCE_PROGRESS=0 ");
    ASSERT_EQ(frames.status, 0) << frames.output;
    std::vector<bounce::core::Image> image, reference;
    std::vector<double> error;
    double sum = 0.0;
    for (std::size_t f = 0; f < cameras.size(); ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "frame-%04zu.exr", f);
        image.push_back(bounce::core::readImage((d / "frames" / name).string()));
        const fs::path ref = d / ("ref-" + std::to_string(f) + ".exr");
        const CommandRun r = bounce::testing::runBounce("reference --scene cornell-spot --camera " + cameras[f] +
                                                        " --paths direct --size 16x16 --spp 64 --cache-dir " + cache +
                                                        " --out " + ref.string());
        ASSERT_EQ(r.status, 0) << r.output;
        reference.push_back(bounce::core::readImage(ref.string()));
        const double e = relativeRmseOf(image[f], reference[f]);
        error.push_back(e);
        sum += e;
        const nlohmann::json& fr = q["frames"][f];
        EXPECT_NEAR(fr.at("relativeRmse").get<double>(), e, 1e-4 * e) << "frame " << f;
        EXPECT_EQ(fr.contains("flicker"), f % 2 == 1) << "frame " << f << ": the pairs are (0, 1) and (2, 3)";
    }
    EXPECT_NEAR(q.at("meanRelativeRmse").get<double>(), sum / 4.0, 1e-4 * sum / 4.0);
    const double flicker = 0.5 * (flickerOf(image[0], reference[0], image[1], reference[1]) +
                                  flickerOf(image[2], reference[2], image[3], reference[3]));
    EXPECT_NEAR(q.at("flicker").get<double>(), flicker, 1e-4 * flicker);
    // The second half's pairs: (2, 3) alone, the pair after the history's start left out.
    const double secondHalfFlicker = flickerOf(image[2], reference[2], image[3], reference[3]);
    EXPECT_NEAR(q.at("secondHalfFlicker").get<double>(), secondHalfFlicker, 1e-4 * secondHalfFlicker);

    std::vector<double> still(cameras.size(), 0.0);
    for (std::size_t f = 0; f < cameras.size(); f += 2) {
        const fs::path at = d / ("still-" + std::to_string(f) + ".exr");
        const CommandRun r = bounce::testing::runBounce(
            "render --scene cornell-spot --technique direct --size 16x16 --backend " + testBackend() + " --camera " +
                cameras[f] + " --warmup 0 --frames 2 --out " + at.string(),
            "BOUNCE_PROGRESS=0 ");
        ASSERT_EQ(r.status, 0) << r.output;
        still[f] = relativeRmseOf(bounce::core::readImage(at.string()), reference[f]);
        EXPECT_NEAR(q["frames"][f].at("stillRelativeRmse").get<double>(), still[f], 1e-4 * still[f]) << "frame " << f;
    }
    const double ratio = 0.5 * (error[0] / still[0] + error[2] / still[2]);
    EXPECT_NEAR(q.at("meanStillRatio").get<double>(), ratio, 1e-4 * ratio);
    const double secondHalf = 0.5 * (error[2] + error[3]) / still[2];
    EXPECT_NEAR(q.at("secondHalfStillRatio").get<double>(), secondHalf, 1e-4 * secondHalf);
    std::printf("[ measured ] direct along 4 frames: mean relative RMSE %.4g, flicker %.4g\n", sum / 4.0, flicker);
}
