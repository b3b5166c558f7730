// The bench's files for a render that wrote NaN/Inf: every error figure of its row is infinite in the CSV
// (with the count of non-finite values in its own column), in results.json (as "inf": JSON has no
// infinity) and in report.md, which says the render failed; the other rows keep their figures.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "app/bench_config.h"
#include "app/bench_images.h"
#include "app/bench_report.h"
#include "app/bench_run.h"

namespace bounce::app {
namespace {

namespace fs = std::filesystem;

BenchRow row(const std::string& technique, double error)
{
    BenchRow r;
    r.scene = "cornell-spot";
    r.technique = technique;
    r.settings = "defaults";
    r.size = "16x16";
    r.lightPaths = "direct";
    r.totalMs = 1.0;
    r.relRmseOwn = r.relRmseFull = r.rmseOwn = error;
    r.ssimOwn = 0.9;
    r.relRmseBaseline = r.flicker = NAN;
    r.relRmseCompareTo = {error};
    r.record = {{"technique", technique}, {"settings", "defaults"}, {"size", "16x16"},
                {"lightPaths", "direct"}, {"totalMs", 1.0},         {"passes", nlohmann::json::array()}};
    for (const char* paths : {"direct", "full", "onebounce"})
        r.record["error"][paths] = {{"rmse", error}, {"relativeRmse", error}, {"ssim", 0.9}, {"maxError", error}};
    return r;
}

std::vector<std::string> csvLine(const std::string& line)
{
    std::vector<std::string> out(1);
    for (char c : line)
        if (c == ',')
            out.emplace_back();
        else
            out.back().push_back(c);
    return out;
}

TEST(BenchReport, NonFiniteRenderHasInfiniteErrorsEverywhere)
{
    const fs::path d = fs::path(BOUNCE_TEST_OUT) / "bench-report";
    fs::remove_all(d);
    fs::create_directories(d);
    BenchConfig config;
    config.sceneNames = {"cornell-spot"};
    config.compareTo = {"onebounce"};
    std::vector<BenchRow> rows = {row("direct", 0.05), row("rsm", 0.0)};
    rows[1].nonFiniteValues = 12;
    rows[1].record["nonFiniteValues"] = 12;
    markNonFinite(rows[1]);
    gl::ContextInfo context;
    writeBenchReport(d, config, rows, {}, context);

    std::ifstream csv(d / "results.csv");
    std::string header, good, bad;
    std::getline(csv, header);
    std::getline(csv, good);
    std::getline(csv, bad);
    const std::vector<std::string> names = csvLine(header), g = csvLine(good), b = csvLine(bad);
    const auto column = [&names](const std::string& name) {
        for (std::size_t i = 0; i < names.size(); ++i)
            if (names[i] == name) return i;
        ADD_FAILURE() << "no column " << name;
        return std::size_t(0);
    };
    for (const char* c : {"rel_rmse_own", "rel_rmse_full", "rmse_own", "rel_rmse_onebounce"}) {
        EXPECT_EQ(b.at(column(c)), "inf") << c;
        EXPECT_EQ(g.at(column(c)), "0.05") << c;
    }
    EXPECT_EQ(b.at(column("ssim_own")), "0");
    EXPECT_EQ(b.at(column("nonfinite_values")), "12");
    EXPECT_EQ(g.at(column("nonfinite_values")), "0");

    const nlohmann::json results = nlohmann::json::parse(std::ifstream(d / "results.json"));
    for (const char* paths : {"direct", "full", "onebounce"}) {
        EXPECT_EQ(results[1]["error"][paths]["relativeRmse"], "inf") << paths;
        EXPECT_EQ(results[1]["error"][paths]["rmse"], "inf") << paths;
        EXPECT_EQ(results[1]["error"][paths]["ssim"], 0.0) << paths;
        EXPECT_EQ(results[0]["error"][paths]["relativeRmse"], 0.05) << paths;
    }
    std::stringstream md;
    md << std::ifstream(d / "report.md").rdbuf();
    EXPECT_NE(md.str().find("Failed: rsm"), std::string::npos) << md.str();
    EXPECT_EQ(md.str().find("Failed: direct"), std::string::npos);
}

// The images report.html loads: base64 as RFC 4648's test vectors give it, and the radiance as little-endian
// IEEE half floats (1 -> 0x3c00, -2 -> 0xc000, 65536 beyond the range -> +inf 0x7c00, NaN stays NaN).
TEST(BenchReport, ImageScriptsCarryHalfFloatsInBase64)
{
    EXPECT_EQ(base64(""), "");
    EXPECT_EQ(base64("f"), "Zg==");
    EXPECT_EQ(base64("fo"), "Zm8=");
    EXPECT_EQ(base64("foo"), "Zm9v");
    EXPECT_EQ(base64("foob"), "Zm9vYg==");
    EXPECT_EQ(base64("fooba"), "Zm9vYmE=");
    EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
    EXPECT_EQ(base64(std::string("\xff\x00\xfe", 3)), "/wD+");

    // Decoded here bit by bit, independently of the encoder.
    const auto halvesOf = [](const std::string& script) {
        const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        const std::size_t at = script.find(", \"") + 3;
        const std::string b = script.substr(at, script.find('"', at) - at);
        std::vector<std::uint16_t> out;
        std::uint32_t bits = 0;
        int count = 0;
        std::string bytes;
        for (char c : b) {
            if (c == '=') break;
            bits = bits << 6 | std::uint32_t(alphabet.find(c));
            count += 6;
            if (count >= 8) {
                count -= 8;
                bytes += char(bits >> count & 0xff);
            }
        }
        for (std::size_t k = 0; k + 1 < bytes.size(); k += 2)
            out.push_back(std::uint16_t((unsigned char)bytes[k] | (unsigned char)bytes[k + 1] << 8));
        return out;
    };
    core::Image image(2, 1);
    image.rgb = {1.0f, -2.0f, 65536.0f, 0.0f, NAN, 0.5f};
    const std::string script = imageScript("images/x", image);
    EXPECT_EQ(script.rfind("bounceImage(\"images/x\", 2, 1, \"", 0), 0u) << script;
    const std::vector<std::uint16_t> h = halvesOf(script);
    ASSERT_EQ(h.size(), 6u) << script;
    EXPECT_EQ(h[0], 0x3c00);
    EXPECT_EQ(h[1], 0xc000);
    EXPECT_EQ(h[2], 0x7c00);
    EXPECT_EQ(h[3], 0x0000);
    EXPECT_EQ(h[4] & 0x7c00, 0x7c00);
    EXPECT_NE(h[4] & 0x03ff, 0) << "NaN, not infinity";
    EXPECT_EQ(h[5], 0x3800);
}

// bench/study.json's split: runs marked "full" and the scenes of "fullScenes" only with --full, yet checked
// (a typo in them fails the quick run too).
TEST(BenchReport, FullRunsAndScenesOnlyWithFull)
{
    const fs::path dir = fs::path(BOUNCE_TEST_OUT) / "bench-full";
    fs::create_directories(dir);
    const fs::path config = dir / "split.json";
    std::ofstream(config) << R"({"scenes": ["cornell-spot"], "fullScenes": ["cornell-point"],
        "runs": [{"technique": "direct"}, {"technique": "rsm", "full": true, "scenes": ["cornell-point"]}]})";
    const BenchConfig quick = readBenchConfig(config.string(), (dir / "cache").string());
    EXPECT_EQ(quick.sceneNames, std::vector<std::string>{"cornell-spot"});
    ASSERT_EQ(quick.settings.size(), 1u);
    EXPECT_EQ(quick.settings[0].technique, "direct");
    const BenchConfig full = readBenchConfig(config.string(), (dir / "cache").string(), true);
    EXPECT_EQ(full.sceneNames, (std::vector<std::string>{"cornell-spot", "cornell-point"}));
    EXPECT_EQ(full.scenes.size(), 2u);
    ASSERT_EQ(full.settings.size(), 2u);
    EXPECT_TRUE(full.settings[1].fullOnly);

    std::ofstream(config) << R"({"scenes": ["cornell-spot"],
        "runs": [{"technique": "direct"}, {"technique": "rsm", "full": true, "set": {"vpl": 4}}]})";
    EXPECT_THROW(readBenchConfig(config.string(), (dir / "cache").string()), std::exception)
        << "a full run's typo fails the quick run";
}

} // namespace
} // namespace bounce::app
