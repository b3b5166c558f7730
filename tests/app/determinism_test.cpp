// Determinism: the same `bounce render` command twice gives bit-identical EXRs on one machine, for every
// registered technique (one case each, from gl::techniques(): a new technique is covered without a line
// here). Benchmarks compare images across runs and cache references by content; an image that changes
// from run to run would make every such comparison noisy. Two frames after a warm-up frame, so that
// per-frame work (VPL clusters, progressive accumulation) is repeated too.
//
// What breaks determinism on a GPU is work ordered by thread timing (an atomic append feeding a float
// sum), so a broken technique differs only in some runs. cornell-point is rendered as well as cornell-spot:
// its six shadow-cube views give six times the parallel work, and llvmpipe reordered isr's atomically
// appended VPLs in about nine runs of ten there (before the clusters were compacted in patch order). The
// test can thus miss a broken technique by luck, but never fails a correct one.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/wait.h>

#include "core/image.h"
#include "gl/technique/technique.h"
#include "tests/app/test_backend.h"

namespace {

namespace fs = std::filesystem;
using bounce::testing::testBackend;

std::vector<std::string> techniqueNames()
{
    std::vector<std::string> names;
    for (const bounce::gl::TechniqueInfo& t : bounce::gl::techniques()) names.push_back(t.name);
    return names;
}

// Runs `bounce args` with new GL storage poisoned (gl/resource/allocations.h: two runs agree only if no
// pass reads what none wrote); the output (stdout and stderr) when it fails, empty when it exits 0.
std::string renderFails(const std::string& args)
{
    const std::string cmd = "BOUNCE_POISON_STORAGE=1 " + std::string(BOUNCE_BINARY) + " " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return "cannot run " + cmd;
    std::string output;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, p)) output += buf;
    const int status = pclose(p);
    return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? std::string() : cmd + "\n" + output;
}

std::string readBytes(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Where two images differ, in words: the number of differing values and the largest difference.
std::string difference(const fs::path& a, const fs::path& b)
{
    const bounce::core::Image x = bounce::core::readImage(a.string()), y = bounce::core::readImage(b.string());
    if (x.width != y.width || x.height != y.height) return "different sizes";
    std::size_t values = 0;
    double largest = 0.0;
    for (std::size_t i = 0; i < x.rgb.size(); ++i)
        if (x.rgb[i] != y.rgb[i]) {
            ++values;
            largest = std::max(largest, double(std::abs(x.rgb[i] - y.rgb[i])));
        }
    char largestText[32];
    std::snprintf(largestText, sizeof largestText, "%.3g", largest);
    return std::to_string(values) + " of " + std::to_string(x.rgb.size()) + " values differ, the largest by " +
           largestText + (values == 0 ? " (the pixels agree; the files do not)" : "");
}

class Determinism : public ::testing::TestWithParam<std::string> {};

TEST_P(Determinism, SameCommandTwiceGivesTheSameExr)
{
    const std::string technique = GetParam();
    for (const std::string scene : {"cornell-spot", "cornell-point"}) {
        const fs::path d = fs::path(BOUNCE_TEST_OUT) / "determinism" / technique / scene;
        fs::remove_all(d);
        fs::create_directories(d);
        std::string command = "render --size 32x32 --frames 2 --warmup 1 --backend " + testBackend() + " --scene " +
                              scene + " --technique " + technique;
        for (const std::string& kv : bounce::gl::findTechnique(technique).quickSets) command += " --set " + kv;
        command += " --out ";
        for (const char* run : {"first", "second"}) {
            const std::string failure = renderFails(command + (d / (std::string(run) + ".exr")).string());
            ASSERT_EQ(failure, "") << "the " << run << " run on " << scene << " failed";
        }
        const fs::path first = d / "first.exr", second = d / "second.exr";
        EXPECT_TRUE(readBytes(first) == readBytes(second))
            << technique << " gave two different EXRs for one command on " << scene << ": " << difference(first, second)
            << " (" << first << ", " << second << ")";
    }
}

INSTANTIATE_TEST_SUITE_P(Every, Determinism, ::testing::ValuesIn(techniqueNames()),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                             std::string n = p.param;
                             for (char& c : n)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return n;
                         });

} // namespace
