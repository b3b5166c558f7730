// Malformed, truncated, inconsistent and unsafe glTF input: every case must throw SceneError whose
// message names the file and the problem, never crash or read outside the scene's folder.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/gltf_io.h"
#include "gltf_bad_cases.h"
#include "gltf_test_builder.h"

namespace bounce::core {
namespace {

using test::json;
using test::fs::path;

// Loads file and expects a SceneError naming the file and containing `word`.
void expectRefused(const std::string& file, const std::string& word)
{
    try {
        loadGltf(file);
        ADD_FAILURE() << file << ": loaded, but should have been refused (" << word << ")";
    } catch (const SceneError& e) {
        const std::string message = e.what();
        ::testing::Test::RecordProperty("message", message); // shown in --gtest_output=xml reports
        EXPECT_NE(message.find(path(file).filename().string()), std::string::npos) << "names the file: " << message;
        EXPECT_NE(message.find(word), std::string::npos) << "says '" << word << "': " << message;
    }
}

TEST(GltfBadInput, TruncatedJson)
{
    const path dir = test::scratchDir();
    const std::string file = test::oneTriangle().writeGltf(dir, "truncated");
    const std::string text = test::readFile(file);
    test::writeFile(file, text.substr(0, text.size() / 2));
    expectRefused(file, "malformed JSON");
}

TEST(GltfBadInput, MalformedJson)
{
    const path dir = test::scratchDir();
    test::writeFile(dir / "garbage.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [ {\"mesh\": 0,, } ]}");
    expectRefused((dir / "garbage.gltf").string(), "malformed JSON");
}

TEST(GltfBadInput, JsonThatIsNotGltf)
{
    const path dir = test::scratchDir();
    test::writeFile(dir / "array.gltf", "[1, 2, 3]");
    expectRefused((dir / "array.gltf").string(), "invalid glTF");
}

TEST(GltfBadInput, TruncatedGlb)
{
    const path dir = test::scratchDir();
    const std::string file = test::oneTriangle().writeGlb(dir, "cut");
    const std::string bytes = test::readFile(file);
    test::writeFile(file, bytes.substr(0, bytes.size() - 16));
    expectRefused(file, "truncated");
}

TEST(GltfBadInput, IndexValueOutOfRange)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    b.doc["meshes"][0]["primitives"][0]["indices"] = b.indices({0, 1, 3}); // 3 vertices: 3 is one too many
    expectRefused(b.writeGltf(dir, "index"), "index 3 is out of range");
}

TEST(GltfBadInput, AccessorIndexOutOfRange)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 42;
    expectRefused(b.writeGltf(dir, "accessor"), "accessor 42 is out of range");
}

TEST(GltfBadInput, AccessorOffsetBeyondBufferView)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    b.doc["accessors"][0]["byteOffset"] = 1024;
    expectRefused(b.writeGltf(dir, "offset"), "beyond the end of bufferView");
}

TEST(GltfBadInput, BufferViewBeyondBuffer)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    b.doc["bufferViews"][0]["byteOffset"] = 4096;
    expectRefused(b.writeGltf(dir, "view"), "beyond the end of buffer");
}

TEST(GltfBadInput, ImageBufferViewBeyondBuffer)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    b.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 1 << 20}, {"byteLength", 64}});
    b.doc["images"] = {{{"bufferView", 1}, {"mimeType", "image/png"}}};
    expectRefused(b.writeGltf(dir, "imageview"), "beyond the end of buffer");
}

TEST(GltfBadInput, AccessorWithoutBufferView)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    b.doc["accessors"][0].erase("bufferView");
    b.doc["accessors"][0]["count"] = 1 << 27; // zeros, bounded by nothing in the file
    expectRefused(b.writeGltf(dir, "noview"), "no bufferView");
}

TEST(GltfBadInput, CountTimesStrideBeyondBuffer)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    b.doc["accessors"][0]["count"] = 1000; // the view holds 3 positions
    expectRefused(b.writeGltf(dir, "count"), "beyond the end of bufferView");
}

TEST(GltfBadInput, AbsurdCount)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    b.doc["accessors"][0]["count"] = 1ull << 40;
    expectRefused(b.writeGltf(dir, "absurd"), "exceeds the limit");
}

TEST(GltfBadInput, MissingBuffer)
{
    const path dir = test::scratchDir();
    const std::string file = test::oneTriangle().writeGltf(dir, "nobin");
    test::fs::remove(dir / "nobin.bin");
    expectRefused(file, "missing file 'nobin.bin'");
}

TEST(GltfBadInput, BufferShorterThanDeclared)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    const std::string file = b.writeGltf(dir, "short");
    test::writeFile(dir / "short.bin", b.bin.substr(0, 8));
    expectRefused(file, "size mismatch");
}

TEST(GltfBadInput, MissingImage)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    b.doc["images"] = {{{"uri", "nowhere.png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    expectRefused(b.writeGltf(dir, "noimage"), "missing");
}

TEST(GltfBadInput, UndecodableImage)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    test::writeFile(dir / "junk.png", "this is not a png");
    b.doc["images"] = {{{"uri", "junk.png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    expectRefused(b.writeGltf(dir, "badimage"), "cannot be decoded");
}

TEST(GltfBadInput, UriLeavingTheFolderIsRefused)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    test::fs::create_directories(dir / "scene");
    const std::string file = b.writeGltf(dir / "scene", "escape");
    test::writeFile(dir / "outside.bin", b.bin); // exists, so only the refusal can stop it
    json doc = json::parse(test::readFile(file));
    doc["buffers"][0]["uri"] = "../outside.bin";
    test::writeFile(file, doc.dump());
    expectRefused(file, "leaves the scene's folder");
}

TEST(GltfBadInput, EncodedDotDotIsRefused)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    test::fs::create_directories(dir / "scene");
    const std::string file = b.writeGltf(dir / "scene", "encoded");
    test::writeFile(dir / "outside.bin", b.bin);
    json doc = json::parse(test::readFile(file));
    doc["buffers"][0]["uri"] = "%2e%2e/outside.bin";
    test::writeFile(file, doc.dump());
    expectRefused(file, "leaves the scene's folder");
}

TEST(GltfBadInput, AbsoluteUriIsRefused)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    const std::string file = b.writeGltf(dir, "absolute");
    json doc = json::parse(test::readFile(file));
    doc["buffers"][0]["uri"] = (dir / "absolute.bin").string(); // exists, but named absolutely
    test::writeFile(file, doc.dump());
    expectRefused(file, "leaves the scene's folder");
}

TEST(GltfBadInput, NanPosition)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b;
    const int pos = b.positions({0, 0, 0, std::nanf(""), 0, 0, 0, 1, 0});
    b.mesh({{"attributes", {{"POSITION", pos}}}});
    b.node({{"mesh", 0}});
    expectRefused(b.writeGltf(dir, "nan"), "NaN");
}

TEST(GltfBadInput, InfinitePosition)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b;
    const int pos = b.positions({0, 0, 0, 1, 0, 0, 0, std::numeric_limits<float>::infinity(), 0});
    b.mesh({{"attributes", {{"POSITION", pos}}}});
    b.node({{"mesh", 0}});
    expectRefused(b.writeGltf(dir, "inf"), "Inf");
}

TEST(GltfBadInput, NodeCycle)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    b.doc["nodes"] = {{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}};
    expectRefused(b.writeGltf(dir, "cycle"), "cycle");
}

TEST(GltfBadInput, NodeIndexOutOfRange)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    b.doc["nodes"][0]["children"] = {7};
    expectRefused(b.writeGltf(dir, "child"), "node 7 is out of range");
}

TEST(GltfBadInput, MaterialIndexOutOfRange)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b = test::oneTriangle();
    b.doc["meshes"][0]["primitives"][0]["material"] = 3;
    expectRefused(b.writeGltf(dir, "material"), "material 3 is out of range");
}

TEST(GltfBadInput, MissingFile)
{
    const path dir = test::scratchDir();
    expectRefused((dir / "absent.gltf").string(), "cannot open");
}

// The generated set (gltf_bad_cases.h): each refused case throws SceneError naming the file and saying
// the case's words; each allowed case loads into a valid scene. tests/app/cli_test.cpp renders the same
// set through `bounce render`.
TEST(GltfBadInput, GeneratedCases)
{
    const path root = test::scratchDir();
    for (const test::BadGltfCase& c : test::badGltfCases()) {
        SCOPED_TRACE(c.name);
        const path dir = root / c.name;
        test::fs::create_directories(dir);
        const std::string file = c.write(dir);
        if (c.words.empty()) {
            try {
                EXPECT_EQ(loadGltf(file).validate(), "");
            } catch (const SceneError& e) {
                ADD_FAILURE() << "refused, but glTF allows it: " << e.what();
            }
            continue;
        }
        expectRefused(file, c.words);
    }
}

constexpr int kFuzzRounds = 400; // a second or less per test in a release build

// Loads a mutated file: it must either load into a valid scene or throw SceneError, nothing else.
void expectLoadsOrRefuses(const std::string& file, const std::string& mutation)
{
    try {
        const Scene s = loadGltf(file);
        EXPECT_EQ(s.validate(), "") << mutation;
    } catch (const SceneError&) {
    } catch (const std::exception& e) {
        ADD_FAILURE() << mutation << ": unexpected exception: " << e.what();
    }
}

// Values of a written scene's file, one at a time, replaced by hostile ones or removed (fixed seed:
// reproducible).
void fuzzValues(const Scene& scene, const path& dir, unsigned seed)
{
    const std::string file = (dir / "fuzz.gltf").string();
    writeGltf(scene, file);
    const json original = json::parse(test::readFile(file));
    std::vector<json::json_pointer> leaves;
    const json flat = original.flatten();
    for (const auto& [key, value] : flat.items()) leaves.emplace_back(key);

    const std::vector<json> hostile = {-1,
                                       0,
                                       1,
                                       2,
                                       3,
                                       7,
                                       255,
                                       65535,
                                       2147483647,
                                       2147483648.0,
                                       4294967296.0,
                                       1e300,
                                       -1e300,
                                       0.5,
                                       1 << 28,
                                       "x",
                                       "../../etc/passwd",
                                       json::array(),
                                       json::object(),
                                       nullptr};
    std::mt19937 rng(seed);
    for (int round = 0; round < kFuzzRounds; ++round) {
        json doc = original;
        const json::json_pointer& where = leaves[rng() % leaves.size()];
        std::string mutation = where.to_string();
        if (round % 5 == 0) {
            doc[where.parent_pointer()].is_object() ? void(doc[where.parent_pointer()].erase(where.back()))
                                                    : void(doc[where] = nullptr);
            mutation += " removed";
        } else {
            const json& value = hostile[rng() % hostile.size()];
            doc[where] = value;
            mutation += " = " + value.dump();
        }
        test::writeFile(file, doc.dump());
        expectLoadsOrRefuses(file, mutation);
    }
}

TEST(GltfBadInput, HostileValuesNeverCrash)
{
    Scene cornell = makeCornell("cornell-spot");
    cornell.meshes.resize(2); // small, so the whole run stays fast
    fuzzValues(cornell, test::scratchDir(), 1234);
}

TEST(GltfBadInput, HostileTextureValuesNeverCrash)
{
    Scene s;
    s.textures.push_back({"t", 2, 2, std::vector<std::uint8_t>(16, 200)});
    Material m;
    m.baseColorTexture = 0;
    s.materials.push_back(m);
    Mesh quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.normals.assign(4, {0, 0, 1});
    quad.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    s.meshes.push_back(quad);
    fuzzValues(s, test::scratchDir(), 99);
}

// Random bytes of a GLB overwritten or cut off.
TEST(GltfBadInput, CorruptGlbBytesNeverCrash)
{
    const path dir = test::scratchDir();
    test::GltfBuilder b;
    const int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
    const int nrm = b.normals({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});
    const int idx = b.indices({0, 1, 2, 2, 1, 3});
    b.mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}, {"indices", idx}});
    b.node({{"mesh", 0}});
    const std::string file = b.writeGlb(dir, "fuzz");
    const std::string original = test::readFile(file);
    std::mt19937 rng(4321);
    for (int round = 0; round < kFuzzRounds; ++round) {
        std::string bytes = original;
        if (round % 4 == 0)
            bytes.resize(rng() % bytes.size());
        else
            for (int k = 0; k < 1 + round % 3; ++k) bytes[rng() % bytes.size()] = char(rng());
        test::writeFile(file, bytes);
        expectLoadsOrRefuses(file, "round " + std::to_string(round));
    }
}

} // namespace
} // namespace bounce::core
