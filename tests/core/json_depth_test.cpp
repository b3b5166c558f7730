// The nesting-depth guard in front of tinygltf: a glTF whose JSON nests ~30,000 levels deep (60 KB)
// crashed every command with a stack overflow inside tinygltf's recursive value conversion.
#include <string>

#include <gtest/gtest.h>

#include "core/gltf_io.h"
#include "core/json_depth.h"
#include "io_test_util.h"

namespace bounce::core {
namespace {

std::size_t depthOf(const std::string& s)
{
    return jsonNestingDepth(s.data(), s.data() + s.size());
}

TEST(JsonDepth, CountsArraysAndObjectsNotStrings)
{
    EXPECT_EQ(depthOf(""), 0u);
    EXPECT_EQ(depthOf("42"), 0u);
    EXPECT_EQ(depthOf("{\"a\": [1, {\"b\": []}]}"), 4u);
    EXPECT_EQ(depthOf("[\"[[[[\", \"{{{\"]"), 1u) << "brackets inside strings do not nest";
    EXPECT_EQ(depthOf("[\"\\\"[[[\"]"), 1u) << "an escaped quote does not end the string";
    EXPECT_EQ(depthOf("[\"\\\\\", [[]]]"), 3u) << "an escaped backslash does";
    EXPECT_EQ(depthOf("]]]]][[]"), 2u) << "stray closers never go below zero";
}

std::string nested(std::size_t depth)
{
    return std::string(depth, '[') + std::string(depth, ']');
}

// The finding: depth 30,000 killed the process (exit 139). Refused with a message instead, by the
// loader, before tinygltf sees it.
TEST(JsonDepth, DeeplyNestedGltfIsRefusedNotCrashed)
{
    const test::fs::path dir = test::scratchDir();
    for (std::size_t depth : {std::size_t(kMaxGltfJsonDepth + 1), std::size_t(30000)}) {
        const std::string file = (dir / ("deep-" + std::to_string(depth) + ".gltf")).string();
        test::writeFile(file, "{\"asset\": {\"version\": \"2.0\", \"extras\": " + nested(depth) + "}}");
        try {
            loadGltf(file);
            ADD_FAILURE() << "loaded a glTF nesting " << depth << " levels";
        } catch (const SceneError& e) {
            EXPECT_NE(std::string(e.what()).find("levels deep"), std::string::npos) << e.what();
        }
    }
}

// A legitimate glTF with extras nested a few levels still loads.
TEST(JsonDepth, ShallowExtrasStillLoad)
{
    const test::fs::path dir = test::scratchDir();
    const std::string file = (dir / "shallow.gltf").string();
    test::writeFile(file, "{\"asset\": {\"version\": \"2.0\", \"extras\": " + nested(20) +
                              "}, \"scenes\": [{\"nodes\": []}], \"scene\": 0}");
    try {
        loadGltf(file);
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()).find("levels deep"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace bounce::core
