// A generated set of malformed, forbidden and hostile glTF/GLB files, one per case, each with the words
// its refusal must say: framing, accessors, URIs, data URIs, images, the node hierarchy, lights, cameras
// and limits. The loader test (gltf_bad_input_test.cpp) loads each; the CLI test (tests/app) renders each
// through `bounce render` (exit status 2 and the message, nothing written). A case with no words must
// load (what glTF allows but the renderer ignores, with a warning).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gltf_test_builder.h"

namespace bounce::core::test {

struct BadGltfCase {
    std::string name;
    std::string words;                                     // what the message must contain; empty: the file loads
    std::function<std::string(const fs::path& dir)> write; // writes the case's files, returns the scene's path
};

// One triangle with a KHR_lights_punctual light on a second node; `light` is the light's JSON.
inline GltfBuilder litTriangle(const json& light)
{
    GltfBuilder b = oneTriangle();
    b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array({light});
    b.node({{"translation", {0.0, 0.0, 1.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.doc["scenes"][0]["nodes"] = {0, 1};
    return b;
}

// One triangle seen by a perspective camera at z = 2 (looking down -z) with these properties.
inline GltfBuilder viewedTriangle(const json& perspective)
{
    GltfBuilder b = oneTriangle();
    b.doc["cameras"] = json::array({{{"type", "perspective"}, {"perspective", perspective}}});
    b.node({{"translation", {0.0, 0.0, 2.0}}, {"camera", 0}});
    b.doc["scenes"][0]["nodes"] = {0, 1};
    return b;
}

// A base-colour texture whose image is `uri` (a file the case writes, or a data URI).
inline GltfBuilder texturedTriangle(const std::string& uri)
{
    GltfBuilder b = oneTriangle();
    b.doc["images"] = {{{"uri", uri}}};
    b.doc["textures"] = {{{"source", 0}}};
    b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    return b;
}

// The first 33 bytes of a PNG whose header says width x height (the CRC is not checked before the size).
inline std::string pngHeader(std::uint32_t width, std::uint32_t height)
{
    std::string s = "\x89PNG\r\n\x1a\n";
    const auto be = [&s](std::uint32_t v) {
        for (int i = 3; i >= 0; --i) s.push_back(char((v >> (8 * i)) & 0xFF));
    };
    be(13);
    s += "IHDR";
    be(width);
    be(height);
    s += std::string("\x08\x06\x00\x00\x00", 5); // 8 bits, RGBA, no interlace
    be(0);                                       // CRC
    return s;
}

// Writes `b` as name.gltf, then replaces its buffer's URI.
inline std::string withBufferUri(GltfBuilder b, const fs::path& dir, const std::string& name, const std::string& uri)
{
    const std::string file = b.writeGltf(dir, name);
    json doc = json::parse(readFile(file));
    doc["buffers"][0]["uri"] = uri;
    writeFile(file, doc.dump());
    return file;
}

inline std::vector<BadGltfCase> badGltfCases()
{
    using W = std::function<std::string(const fs::path&)>;
    std::vector<BadGltfCase> cases;
    const auto add = [&cases](std::string name, std::string words, W write) {
        cases.push_back({std::move(name), std::move(words), std::move(write)});
    };
    // Modifies the one-triangle file's JSON and writes it as a .gltf.
    const auto edited = [](std::function<void(GltfBuilder&)> edit) -> W {
        return [edit](const fs::path& dir) {
            GltfBuilder b = oneTriangle();
            edit(b);
            return b.writeGltf(dir, "scene");
        };
    };

    // ---- framing
    add("truncated-json", "malformed JSON", [](const fs::path& dir) {
        const std::string file = oneTriangle().writeGltf(dir, "scene");
        const std::string text = readFile(file);
        writeFile(file, text.substr(0, text.size() / 2));
        return file;
    });
    add("json-array", "invalid glTF", [](const fs::path& dir) {
        writeFile(dir / "scene.gltf", "[1, 2, 3]");
        return (dir / "scene.gltf").string();
    });
    add("empty-file", "malformed JSON", [](const fs::path& dir) {
        writeFile(dir / "scene.gltf", "");
        return (dir / "scene.gltf").string();
    });
    add("glb-truncated", "truncated", [](const fs::path& dir) {
        const std::string file = oneTriangle().writeGlb(dir, "scene");
        const std::string bytes = readFile(file);
        writeFile(file, bytes.substr(0, bytes.size() - 16));
        return file;
    });
    add("glb-bad-magic", "not a GLB", [](const fs::path& dir) {
        const std::string file = oneTriangle().writeGlb(dir, "scene");
        std::string bytes = readFile(file);
        bytes[0] = 'x';
        writeFile(file, bytes);
        return file;
    });
    add("glb-json-chunk-too-long", "bad JSON chunk", [](const fs::path& dir) {
        const std::string file = oneTriangle().writeGlb(dir, "scene");
        std::string bytes = readFile(file);
        bytes[12] = bytes[13] = bytes[14] = char(0x7F); // the JSON chunk's length
        writeFile(file, bytes);
        return file;
    });
    add("deep-nesting", "levels deep", [](const fs::path& dir) {
        // The crash of issue 17: nesting that overflowed the stack in tinygltf's JSON conversion.
        const std::string file = oneTriangle().writeGltf(dir, "scene");
        std::string out = json::parse(readFile(file)).dump();
        out.insert(out.size() - 1, ",\"extras\":" + std::string(30000, '[') + std::string(30000, ']'));
        writeFile(file, out);
        return file;
    });

    // ---- accessors
    add("index-out-of-range", "index 3 is out of range", edited([](GltfBuilder& b) {
            b.doc["meshes"][0]["primitives"][0]["indices"] = b.indices({0, 1, 3});
        }));
    add("accessor-out-of-range", "accessor 42 is out of range",
        edited([](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 42; }));
    add("accessor-beyond-view", "beyond the end of bufferView",
        edited([](GltfBuilder& b) { b.doc["accessors"][0]["byteOffset"] = 1024; }));
    add("view-beyond-buffer", "beyond the end of buffer",
        edited([](GltfBuilder& b) { b.doc["bufferViews"][0]["byteOffset"] = 4096; }));
    add("accessor-without-view", "no bufferView",
        edited([](GltfBuilder& b) { b.doc["accessors"][0].erase("bufferView"); }));
    add("absurd-count", "exceeds the limit", edited([](GltfBuilder& b) { b.doc["accessors"][0]["count"] = 1u << 30; }));
    add("float-indices", "not an unsigned integer type", edited([](GltfBuilder& b) {
            b.doc["meshes"][0]["primitives"][0]["indices"] = b.accessor<float>({0, 1, 2}, "SCALAR", 5126);
        }));
    add("wrong-accessor-type", "wrong type", edited([](GltfBuilder& b) { b.doc["accessors"][0]["type"] = "VEC2"; }));
    add("indices-not-triangles", "whole number of triangles", edited([](GltfBuilder& b) {
            b.doc["meshes"][0]["primitives"][0]["indices"] = b.indices({0, 1});
        }));

    // ---- URIs
    add("uri-dotdot", "leaves the scene's folder", [](const fs::path& dir) {
        fs::create_directories(dir / "scene");
        writeFile(dir / "outside.bin", oneTriangle().bin);
        return withBufferUri(oneTriangle(), dir / "scene", "scene", "../outside.bin");
    });
    add("uri-absolute", "leaves the scene's folder",
        [](const fs::path& dir) { return withBufferUri(oneTriangle(), dir, "scene", (dir / "scene.bin").string()); });
    add("uri-empty", "names a folder or nothing",
        [](const fs::path& dir) { return withBufferUri(oneTriangle(), dir, "scene", ""); });
    add("uri-dot", "names a folder or nothing",
        [](const fs::path& dir) { return withBufferUri(oneTriangle(), dir, "scene", "."); });
    add("uri-folder", "names a folder or nothing", [](const fs::path& dir) {
        fs::create_directories(dir / "sub");
        return withBufferUri(oneTriangle(), dir, "scene", "sub");
    });
    add("uri-missing", "missing file",
        [](const fs::path& dir) { return withBufferUri(oneTriangle(), dir, "scene", "absent.bin"); });

    // ---- data URIs
    add("data-uri-bad-base64", "invalid glTF", [](const fs::path& dir) {
        return withBufferUri(oneTriangle(), dir, "scene", "data:application/octet-stream;base64,!!!!");
    });
    add("data-uri-too-short", "invalid glTF", [](const fs::path& dir) {
        return withBufferUri(oneTriangle(), dir, "scene", "data:application/octet-stream;base64,AAAA");
    });
    add("data-uri-image-garbage", "cannot be decoded", [](const fs::path& dir) {
        return texturedTriangle("data:image/png;base64,bm90IGEgcG5n").writeGltf(dir, "scene");
    });

    // ---- images
    add("image-missing", "missing",
        [](const fs::path& dir) { return texturedTriangle("nowhere.png").writeGltf(dir, "scene"); });
    add("image-undecodable", "cannot be decoded", [](const fs::path& dir) {
        writeFile(dir / "junk.png", "this is not a png");
        return texturedTriangle("junk.png").writeGltf(dir, "scene");
    });
    add("image-claims-100000-squared", "claims 100000x100000", [](const fs::path& dir) {
        writeFile(dir / "huge.png", pngHeader(100000, 100000));
        return texturedTriangle("huge.png").writeGltf(dir, "scene");
    });
    add("image-claims-no-pixels", "claims 0x16", [](const fs::path& dir) {
        writeFile(dir / "empty.png", pngHeader(0, 16));
        return texturedTriangle("empty.png").writeGltf(dir, "scene");
    });
    add("image-view-beyond-buffer", "beyond the end of buffer", edited([](GltfBuilder& b) {
            b.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 1 << 20}, {"byteLength", 64}});
            b.doc["images"] = {{{"bufferView", 1}, {"mimeType", "image/png"}}};
        }));

    // ---- hierarchy
    add("cycle-in-scene", "cycle", edited([](GltfBuilder& b) {
            b.doc["nodes"] = {{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}};
        }));
    add("cycle-without-scene", "lies on a cycle", edited([](GltfBuilder& b) {
            b.doc.erase("scenes");
            b.doc.erase("scene");
            b.doc["nodes"] = {{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}};
        }));
    add("shared-child", "reached twice", edited([](GltfBuilder& b) {
            b.doc["nodes"] = {{{"children", {2}}}, {{"children", {2}}}, {{"mesh", 0}}};
            b.doc["scenes"][0]["nodes"] = {0, 1};
        }));
    add("child-out-of-range", "node 7 is out of range",
        edited([](GltfBuilder& b) { b.doc["nodes"][0]["children"] = {7}; }));
    add("mesh-out-of-range", "mesh 5 is out of range", edited([](GltfBuilder& b) { b.doc["nodes"][0]["mesh"] = 5; }));
    add("material-out-of-range", "material 3 is out of range",
        edited([](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["material"] = 3; }));

    // ---- lights
    const auto lit = [](json light) -> W {
        return [light](const fs::path& dir) { return litTriangle(light).writeGltf(dir, "scene"); };
    };
    add("light-negative-intensity", "is negative", lit({{"type", "point"}, {"intensity", -2.0}}));
    add("light-negative-colour", "colour component is negative",
        lit({{"type", "point"}, {"color", {1.0, -1.0, 1.0}}, {"intensity", 2.0}}));
    add("spot-outer-below-inner", "innerConeAngle < outerConeAngle",
        lit({{"type", "spot"}, {"spot", {{"innerConeAngle", 0.6}, {"outerConeAngle", 0.3}}}}));
    add("spot-outer-beyond-quarter-turn", "innerConeAngle < outerConeAngle",
        lit({{"type", "spot"}, {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 2.0}}}}));
    add("spot-negative-inner", "innerConeAngle < outerConeAngle",
        lit({{"type", "spot"}, {"spot", {{"innerConeAngle", -0.1}, {"outerConeAngle", 0.5}}}}));
    add("light-fractional-index", "not a whole number", [](const fs::path& dir) {
        GltfBuilder b = litTriangle({{"type", "point"}});
        b.doc["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 0.5;
        return b.writeGltf(dir, "scene");
    });
    add("light-index-out-of-range", "light 3 is out of range", [](const fs::path& dir) {
        GltfBuilder b = litTriangle({{"type", "point"}});
        b.doc["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 3;
        return b.writeGltf(dir, "scene");
    });
    add("light-unknown-type", "", lit({{"type", "laser"}})); // skipped with a warning

    // ---- cameras
    const auto viewed = [](json perspective) -> W {
        return [perspective](const fs::path& dir) { return viewedTriangle(perspective).writeGltf(dir, "scene"); };
    };
    add("camera-yfov-pi", "outside (0, pi)", viewed({{"yfov", 3.2}, {"znear", 0.1}, {"zfar", 10.0}}));
    add("camera-yfov-negative", "outside (0, pi)", viewed({{"yfov", -0.5}, {"znear", 0.1}, {"zfar", 10.0}}));
    add("camera-znear-beyond-zfar", "is not beyond znear", viewed({{"yfov", 0.8}, {"znear", 5.0}, {"zfar", 1.0}}));
    add("camera-znear-zero", "is not positive", viewed({{"yfov", 0.8}, {"znear", 0.0}, {"zfar", 10.0}}));
    add("camera-infinite", "", viewed({{"yfov", 0.8}, {"znear", 0.1}})); // no zfar: glTF's infinite projection
    add("camera-out-of-range", "camera 4 is out of range", [](const fs::path& dir) {
        GltfBuilder b = viewedTriangle({{"yfov", 0.8}, {"znear", 0.1}});
        b.doc["nodes"][1]["camera"] = 4;
        return b.writeGltf(dir, "scene");
    });

    // ---- limits and data
    add("nan-position", "NaN", [](const fs::path& dir) {
        GltfBuilder b;
        const int pos = b.positions({0, 0, 0, std::nanf(""), 0, 0, 0, 1, 0});
        b.mesh({{"attributes", {{"POSITION", pos}}}});
        b.node({{"mesh", 0}});
        return b.writeGltf(dir, "scene");
    });
    add("count-over-2^28", "exceeds the limit",
        edited([](GltfBuilder& b) { b.doc["accessors"][0]["count"] = (1u << 28) + 1; }));
    add("points-primitive", "", edited([](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["mode"] = 0; }));
    return cases;
}

} // namespace bounce::core::test
