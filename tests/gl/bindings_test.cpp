// Binding points are named once (glsl/common/bindings.glsl, glsl/technique/<family>/bindings.glsl) and
// used by name on both sides: these tests read the sources and fail on a literal slot number in a
// shader's block or sampler declaration or in a C++ bind call, on two storage names of one number anywhere,
// and on two texture units or uniform blocks sharing a slot where they are bound together. Storage names are
// not slots: each program gives its blocks points of its own (gl/resource/storage_bindings.h), and the
// conformance test checks every program's (no two blocks under one name or at one point, at most 13).
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gl/frame/bindings.h"
#include "gl/technique/grb/bindings.h"
#include "gl/technique/isr/bindings.h"
#include "gl/technique/microrender/bindings.h"
#include "gl/technique/photon/bindings.h"
#include "glsl/frame/sort_bindings.glsl"

namespace fs = std::filesystem;

namespace {

fs::path root()
{
    const char* r = std::getenv("BOUNCE_ROOT");
    return r ? fs::path(r) : fs::path(BOUNCE_SOURCE_ROOT);
}

std::string read(const fs::path& p)
{
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Every line of the files under `dir` (recursively) with these extensions that matches `re`, as
// "path:line: text".
std::vector<std::string> grep(const fs::path& dir, const std::vector<std::string>& exts, const std::regex& re)
{
    std::vector<std::string> hits;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        if (!e.is_regular_file()) continue;
        if (std::find(exts.begin(), exts.end(), e.path().extension().string()) == exts.end()) continue;
        std::istringstream in(read(e.path()));
        std::string line;
        for (int n = 1; std::getline(in, line); ++n)
            if (std::regex_search(line, re)) hits.push_back(e.path().string() + ":" + std::to_string(n) + ": " + line);
    }
    return hits;
}

// name -> value of every "#define NAME value" in a bindings file.
std::map<std::string, int> table(const fs::path& p)
{
    std::map<std::string, int> t;
    const std::regex def(R"(^#define ((SSBO|UBO|UNIT)_\w+) (\d+))");
    std::istringstream in(read(p));
    std::string line;
    std::smatch m;
    while (std::getline(in, line))
        if (std::regex_search(line, m, def)) t[m[1]] = std::stoi(m[3]);
    return t;
}

} // namespace

TEST(Bindings, ShadersDeclareBlocksAndSamplersByName)
{
    // Image units stay literal: each compute pass numbers its own images from 0 (bindings.glsl says so).
    const std::regex literal(
        R"(layout\s*\((std140|std430)?[,\s]*binding\s*=\s*\d+\s*\)|layout\s*\(\s*binding\s*=\s*\d+)");
    std::vector<std::string> hits;
    for (const char* dir : {"glsl/common", "glsl/frame", "glsl/technique", "glsl/probe"})
        for (const std::string& h : grep(root() / dir, {".glsl", ".vert", ".frag", ".comp", ".geom"}, literal))
            hits.push_back(h);
    EXPECT_TRUE(hits.empty()) << "literal binding numbers (name them in a bindings.glsl):\n"
                              << ::testing::PrintToString(hits);
}

TEST(Bindings, CppBindsByName)
{
    const std::regex literal(
        R"((bindBase\(GL_(SHADER_STORAGE|UNIFORM)_BUFFER,\s*\d+\))|(\.bind\(\d+\))|(glBindBufferRange\(GL_\w+,\s*\d+,))");
    std::vector<std::string> hits;
    for (const char* dir : {"gl/frame", "gl/technique", "app"})
        for (const std::string& h : grep(root() / dir, {".cpp", ".h"}, literal)) hits.push_back(h);
    EXPECT_TRUE(hits.empty()) << "literal binding numbers in C++ (use gl/frame/bindings.h):\n"
                              << ::testing::PrintToString(hits);
}

// Every SSBO_* of every bindings.glsl is a number of its own and no other name's alias: a name is what C++
// binds a buffer under, so two meanings under one number would read each other's buffers.
TEST(Bindings, EveryStorageNameIsItsOwn)
{
    std::map<int, std::string> owner; // number -> name (file)
    const std::regex alias(R"(^#define (SSBO_\w+) +([A-Za-z_]\w*))");
    int files = 0;
    for (const auto& e : fs::recursive_directory_iterator(root() / "glsl")) {
        if (e.path().filename() != "bindings.glsl" && e.path().filename() != "sort_bindings.glsl") continue;
        ++files;
        const std::string where = fs::relative(e.path(), root()).string();
        for (const auto& [name, value] : table(e.path())) {
            if (name.rfind("SSBO_", 0) != 0) continue;
            EXPECT_EQ(owner.count(value), 0u)
                << name << " (" << where << ") and " << owner[value] << " are both " << value;
            owner[value] = name + " (" + where + ")";
        }
        std::istringstream in(read(e.path()));
        std::string line;
        while (std::getline(in, line))
            if (std::regex_search(line, alias))
                ADD_FAILURE() << where << ": a storage name defined as another: " << line;
    }
    EXPECT_GE(files, 8);
    EXPECT_NE(SSBO_SCAN_SUMS, SSBO_SORT_COUNTS); // the C++ side is the same files
}

// Texture units and uniform blocks are still slots: those bound in one run must not share one.
TEST(Bindings, NoTwoUnitsShareASlot)
{
    const auto frame = table(root() / "glsl/common/bindings.glsl");
    ASSERT_FALSE(frame.empty());
    // The passes that read no G-buffer (composite, tone map, joint upsampling, the area ratio's resolve)
    // reuse the first units.
    const std::vector<std::string> passLocal{"UNIT_COMPOSITE_DIRECT",         "UNIT_COMPOSITE_INDIRECT",
                                             "UNIT_TONEMAP_RADIANCE",         "UNIT_UPSAMPLE_COARSE_INDIRECT",
                                             "UNIT_UPSAMPLE_COARSE_GEOMETRY", "UNIT_UPSAMPLE_FULL_GEOMETRY",
                                             "UNIT_AREA_UNSHADOWED",          "UNIT_AREA_VISIBILITY"};
    // RSM and multires pyramid names are the first of six units each.
    auto span = [](const std::string& n) { return n == "UNIT_RSM_FIRST" || n == "UNIT_MULTIRES_FIRST" ? 6 : 1; };
    // Tables bound together in one run must not share a slot.
    const auto checkTogether = [&](const std::vector<const std::map<std::string, int>*>& tables) {
        std::map<std::string, std::string> used; // "SSBO 4" -> name
        for (const auto* t : tables)
            for (const auto& [name, value] : *t) {
                if (std::find(passLocal.begin(), passLocal.end(), name) != passLocal.end()) continue;
                const std::string kind = name.substr(0, name.find('_'));
                if (name.rfind("SSBO_", 0) == 0) continue; // storage names: EveryStorageNameIsItsOwn
                for (int i = 0; i < span(name); ++i) {
                    const std::string key = kind + " " + std::to_string(value + i);
                    EXPECT_EQ(used.count(key), 0u) << name << " and " << used[key] << " share " << key;
                    used[key] = name;
                }
            }
    };
    // Families never run together: each is checked against the frame's slots, not against each other;
    // the point families (microrender, pointproj) bind the shared cloud's slots (frame/points/) too.
    std::vector<std::string> families; // every glsl/technique/<family>/bindings.glsl
    for (const auto& e : fs::directory_iterator(root() / "glsl/technique"))
        if (fs::exists(e.path() / "bindings.glsl")) families.push_back(e.path().filename().string());
    ASSERT_GE(families.size(), 2u);
    const auto points = table(root() / "glsl/frame/points/bindings.glsl");
    ASSERT_FALSE(points.empty());
    for (const std::string& family : families) {
        SCOPED_TRACE(family);
        const auto own = table(root() / "glsl/technique" / family / "bindings.glsl");
        ASSERT_FALSE(own.empty());
        if (family == "microrender" || family == "pointproj")
            checkTogether({&frame, &points, &own});
        else
            checkTogether({&frame, &own});
    }
    // The C++ side is the same file: spot-check that the macros are what the table says.
    EXPECT_EQ(SSBO_BVH_NODES, frame.at("SSBO_BVH_NODES"));
    EXPECT_EQ(UNIT_ISR_VPL_TREE_TEXELS,
              table(root() / "glsl/technique/isr/bindings.glsl").at("UNIT_ISR_VPL_TREE_TEXELS"));
    EXPECT_EQ(UNIT_GRB_KBUFFER, table(root() / "glsl/technique/grb/bindings.glsl").at("UNIT_GRB_KBUFFER"));
    EXPECT_EQ(SSBO_PHOTON_NODES, table(root() / "glsl/technique/photon/bindings.glsl").at("SSBO_PHOTON_NODES"));
    EXPECT_EQ(SSBO_MICRO_NODES, table(root() / "glsl/technique/microrender/bindings.glsl").at("SSBO_MICRO_NODES"));
}
