// Builds small glTF files by hand for the loader tests: JSON through nlohmann::json, binary data in
// one buffer, written as .gltf + .bin or as .glb.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io_test_util.h"

namespace bounce::core::test {

using nlohmann::json;

struct GltfBuilder {
    json doc = {{"asset", {{"version", "2.0"}}}};
    std::string bin;

    // Appends raw values as one bufferView + accessor; returns the accessor index.
    template <class T>
    int accessor(const std::vector<T>& values, const char* type, int componentType)
    {
        while (bin.size() % 4) bin.push_back('\0');
        const std::size_t offset = bin.size();
        bin.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
        doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(T)}});
        const std::size_t components = std::string(type) == "VEC3" ? 3 : std::string(type) == "VEC2" ? 2 : 1;
        const std::size_t elementBytes = components * (componentType == 5126 || componentType == 5125 ? 4
                                                       : componentType == 5123                        ? 2
                                                                                                      : 1);
        doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1},
                                    {"componentType", componentType},
                                    {"count", values.size() * sizeof(T) / elementBytes},
                                    {"type", type}});
        return int(doc["accessors"].size()) - 1;
    }
    int positions(const std::vector<float>& xyz) { return accessor(xyz, "VEC3", 5126); }
    int normals(const std::vector<float>& xyz) { return accessor(xyz, "VEC3", 5126); }
    int indices(const std::vector<std::uint32_t>& i) { return accessor(i, "SCALAR", 5125); }

    // Adds a mesh with one primitive; returns the mesh index.
    int mesh(json primitive)
    {
        doc["meshes"].push_back({{"primitives", json::array({primitive})}});
        return int(doc["meshes"].size()) - 1;
    }
    int node(json n)
    {
        doc["nodes"].push_back(n);
        return int(doc["nodes"].size()) - 1;
    }

    // Writes dir/name.gltf and dir/name.bin; returns the .gltf path.
    std::string writeGltf(const fs::path& dir, const std::string& name)
    {
        json d = doc;
        d["buffers"] = json::array({{{"uri", name + ".bin"}, {"byteLength", bin.size()}}});
        writeFile(dir / (name + ".bin"), bin);
        writeFile(dir / (name + ".gltf"), d.dump(1));
        return (dir / (name + ".gltf")).string();
    }

    // Writes dir/name.glb with the buffer in the BIN chunk.
    std::string writeGlb(const fs::path& dir, const std::string& name)
    {
        json d = doc;
        d["buffers"] = json::array({{{"byteLength", bin.size()}}});
        std::string text = d.dump();
        while (text.size() % 4) text.push_back(' ');
        std::string body = bin;
        while (body.size() % 4) body.push_back('\0');
        std::string glb;
        auto u32 = [&glb](std::uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
        glb += "glTF";
        u32(2);
        u32(std::uint32_t(12 + 8 + text.size() + 8 + body.size()));
        u32(std::uint32_t(text.size()));
        u32(0x4E4F534Au); // JSON
        glb += text;
        u32(std::uint32_t(body.size()));
        u32(0x004E4942u); // BIN
        glb += body;
        writeFile(dir / (name + ".glb"), glb);
        return (dir / (name + ".glb")).string();
    }
};

// One triangle, counter-clockwise seen from +z, no normals, no indices, no material.
inline GltfBuilder oneTriangle()
{
    GltfBuilder b;
    const int pos = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    b.mesh({{"attributes", {{"POSITION", pos}}}});
    b.node({{"mesh", 0}});
    b.doc["scenes"] = json::array({{{"nodes", {0}}}});
    b.doc["scene"] = 0;
    return b;
}

} // namespace bounce::core::test
