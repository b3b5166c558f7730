// Writing core::Scene as glTF (core/gltf_io.h says what is kept): a .gltf whose numbers read back as
// the very same floats, and a sibling .bin, each written atomically.
#include "core/gltf_io.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <stb_image_write.h> // implementation in Debian's libstb

#include "core/gltf_files.h"
#include "core/image.h"

namespace bounce::core {

namespace fs = std::filesystem;
using gltf::fail;
using gltf::lowerExtension;

namespace {

constexpr int kTargetArrayBuffer = 34962;
constexpr int kTargetElementArrayBuffer = 34963;

using nlohmann::json;

// The double nearest to the shortest decimal that reads back as f: files show 0.278, not
// 0.27799999713897705, and still load to the very same float. Checked, since a decimal near the middle
// between two floats could round the other way through double.
double decimal(float f)
{
    char text[32];
    const auto [end, ec] = std::to_chars(text, text + sizeof text - 1, f);
    if (ec != std::errc()) return double(f);
    *end = '\0';
    const double d = std::strtod(text, nullptr);
    return float(d) == f ? d : double(f);
}

json vec3Json(const glm::vec3& v)
{
    return {decimal(v.x), decimal(v.y), decimal(v.z)};
}

// The .bin being assembled and the glTF objects that describe it.
struct BinaryWriter {
    std::string bytes;
    json views = json::array();
    json accessors = json::array();

    int addView(const void* data, std::size_t size, int target)
    {
        bytes.resize((bytes.size() + 3) & ~std::size_t(3), '\0'); // every view starts 4-byte aligned
        json view = {{"buffer", 0}, {"byteOffset", bytes.size()}, {"byteLength", size}};
        if (target != 0) view["target"] = target;
        bytes.append(static_cast<const char*>(data), size);
        views.push_back(view);
        return int(views.size()) - 1;
    }

    template <class T>
    int addAccessor(const std::vector<T>& values, const char* type, int componentType, int target, bool minMax = false)
    {
        json a = {{"bufferView", addView(values.data(), values.size() * sizeof(T), target)},
                  {"componentType", componentType},
                  {"count", values.size()},
                  {"type", type}};
        if constexpr (std::is_same_v<T, glm::vec3>) {
            if (minMax) { // required for POSITION
                glm::vec3 lo = values.front(), hi = values.front();
                for (const glm::vec3& v : values) {
                    lo = glm::min(lo, v);
                    hi = glm::max(hi, v);
                }
                a["min"] = vec3Json(lo);
                a["max"] = vec3Json(hi);
            }
        }
        accessors.push_back(a);
        return int(accessors.size()) - 1;
    }
};

// A node placed at `position` whose -z axis is `back` negated (forward) and +y axis is `up`. The
// rotation is written as a quaternion when that reproduces the basis exactly, else as a matrix, so
// that loading gives back the very same vectors.
json frameNode(const glm::vec3& position, const glm::vec3* forward, const glm::vec3* up)
{
    json node;
    if (forward) {
        const glm::dvec3 z = -glm::dvec3(*forward);
        glm::dvec3 y;
        if (up)
            y = glm::dvec3(*up);
        else
            y = std::abs(z.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
        const glm::dvec3 x = glm::normalize(glm::cross(y, z));
        if (!up) y = glm::cross(z, x);
        const glm::dmat3 basis(x, y, z);
        const glm::dquat q = glm::quat_cast(basis);
        if (glm::mat3_cast(q) == basis) {
            if (q != glm::dquat(1, 0, 0, 0))
                node["rotation"] = {q.x + 0.0, q.y + 0.0, q.z + 0.0, q.w + 0.0}; // + 0.0: no -0
        } else {
            node["matrix"] = {x.x,
                              x.y,
                              x.z,
                              0.0,
                              y.x,
                              y.y,
                              y.z,
                              0.0,
                              z.x,
                              z.y,
                              z.z,
                              0.0,
                              decimal(position.x),
                              decimal(position.y),
                              decimal(position.z),
                              1.0};
            return node;
        }
    }
    if (position != glm::vec3(0.0f)) node["translation"] = vec3Json(position);
    return node;
}

// Splits a non-negative colour into a factor in [0,1] (largest component exactly 1) and a scale. The
// loader forms factor x scale in double and rounds once to float, which gives back the very same
// float colour: the scale reads back as the peak float, and the other factors are that component
// divided by the scale in double.
std::pair<json, double> splitColour(const glm::vec3& c)
{
    const float peak = std::max({c.x, c.y, c.z});
    if (!(peak > 0.0f)) return {json{0.0, 0.0, 0.0}, 0.0};
    const double scale = decimal(peak);
    json factor = json::array();
    for (int i = 0; i < 3; ++i) factor.push_back(c[i] == peak ? 1.0 : double(c[i]) / scale);
    return {factor, scale};
}

std::string uriEscape(const std::string& name)
{
    std::string out;
    for (unsigned char c : name) {
        if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~')
            out += char(c);
        else {
            char hex[4];
            std::snprintf(hex, sizeof hex, "%%%02X", c);
            out += hex;
        }
    }
    return out;
}

void appendToString(void* context, void* data, int size)
{
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
}

json materialJson(const Material& m, std::set<std::string>& extensions)
{
    json pbr = {{"baseColorFactor",
                 {decimal(m.baseColor.x), decimal(m.baseColor.y), decimal(m.baseColor.z), decimal(m.baseAlpha)}},
                {"metallicFactor", decimal(m.metallic)},
                {"roughnessFactor", decimal(m.roughness)}};
    if (m.baseColorTexture >= 0) pbr["baseColorTexture"] = {{"index", m.baseColorTexture}};
    json j = {{"name", m.name}, {"pbrMetallicRoughness", pbr}};
    if (m.hasNormalMap()) {
        j["normalTexture"] = {{"index", m.normalTexture}};
        if (m.normalScale != 1.0f) j["normalTexture"]["scale"] = decimal(m.normalScale);
    }
    if (m.doubleSided) j["doubleSided"] = true;
    if (m.isMasked()) {
        j["alphaMode"] = "MASK";
        j["alphaCutoff"] = decimal(m.alphaCutoff);
    }
    if (m.isEmissive()) {
        const float peak = std::max({m.emission.x, m.emission.y, m.emission.z});
        if (peak <= 1.0f)
            j["emissiveFactor"] = vec3Json(m.emission);
        else {
            // emissiveFactor is clamped to [0,1]; the rest goes through KHR_materials_emissive_strength.
            auto [factor, strength] = splitColour(m.emission);
            j["emissiveFactor"] = factor;
            j["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", strength}};
            extensions.insert("KHR_materials_emissive_strength");
        }
    }
    if (m.specular != 1.0f || m.specularColor != glm::vec3(1.0f)) {
        j["extensions"]["KHR_materials_specular"] = {{"specularFactor", decimal(m.specular)},
                                                     {"specularColorFactor", vec3Json(m.specularColor)}};
        extensions.insert("KHR_materials_specular");
    }
    return j;
}

json lightJson(const Light& l)
{
    auto [colour, intensity] = splitColour(l.intensity);
    if (intensity == 0.0) colour = json{1.0, 1.0, 1.0};
    json j = {{"name", l.name}, {"color", colour}, {"intensity", intensity}};
    switch (l.type) {
    case LightType::Point: j["type"] = "point"; break;
    case LightType::Directional: j["type"] = "directional"; break;
    case LightType::Spot: {
        j["type"] = "spot";
        const double outer = decimal(l.outerConeRad);
        double inner = decimal(l.innerConeRad);
        // glTF requires inner < outer. A hard cone (inner == outer) is written with the largest double
        // below the outer angle: it passes validation and still rounds back to the outer float.
        if (l.innerConeRad >= l.outerConeRad) {
            inner = std::nextafter(outer, 0.0);
            if (float(inner) != l.outerConeRad) inner = std::nextafter(double(l.outerConeRad), 0.0);
        }
        j["spot"] = {{"innerConeAngle", inner}, {"outerConeAngle", outer}};
        break;
    }
    }
    return j;
}

} // namespace

void writeGltf(const Scene& scene, const std::string& path)
{
    if (lowerExtension(path) != ".gltf") fail(path, "writeGltf writes .gltf files (with a sibling .bin) only");
    if (std::string problems = scene.validate(); !problems.empty()) {
        while (!problems.empty() && problems.back() == '\n') problems.pop_back();
        fail(path, "cannot write an invalid scene: " + problems);
    }
    const fs::path binPath = fs::path(path).replace_extension(".bin");
    const std::string binName = binPath.filename().string();

    std::set<std::string> extensions;
    BinaryWriter bin;
    json doc;
    doc["asset"] = {{"version", "2.0"}, {"generator", "Bounce core::writeGltf"}};
    json nodes = json::array(), meshes = json::array();

    for (const Mesh& m : scene.meshes) {
        if (m.indices.empty() || m.positions.empty()) continue; // nothing to draw, and glTF forbids empty accessors
        json attributes = {
            {"POSITION", bin.addAccessor(m.positions, "VEC3", TINYGLTF_COMPONENT_TYPE_FLOAT, kTargetArrayBuffer, true)},
            {"NORMAL", bin.addAccessor(m.normals, "VEC3", TINYGLTF_COMPONENT_TYPE_FLOAT, kTargetArrayBuffer)}};
        if (!m.uvs.empty())
            attributes["TEXCOORD_0"] =
                bin.addAccessor(m.uvs, "VEC2", TINYGLTF_COMPONENT_TYPE_FLOAT, kTargetArrayBuffer);
        if (!m.tangents.empty())
            attributes["TANGENT"] =
                bin.addAccessor(m.tangents, "VEC4", TINYGLTF_COMPONENT_TYPE_FLOAT, kTargetArrayBuffer);
        const int indices =
            bin.addAccessor(m.indices, "SCALAR", TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, kTargetElementArrayBuffer);
        json primitive = {{"attributes", attributes}, {"indices", indices}, {"material", m.material}};
        meshes.push_back({{"name", m.name}, {"primitives", json::array({primitive})}});
        nodes.push_back({{"name", m.name}, {"mesh", int(meshes.size()) - 1}});
    }
    doc["meshes"] = meshes;

    json materials = json::array();
    for (const Material& m : scene.materials) materials.push_back(materialJson(m, extensions));
    doc["materials"] = materials;

    if (!scene.textures.empty()) {
        json images = json::array(), textures = json::array();
        for (const Texture& t : scene.textures) {
            if (t.width <= 0 || t.height <= 0 || t.rgba8.size() != std::size_t(t.width) * std::size_t(t.height) * 4)
                fail(path, "texture '" + t.name + "' has inconsistent size");
            std::string png;
            if (!stbi_write_png_to_func(appendToString, &png, t.width, t.height, 4, t.rgba8.data(), t.width * 4))
                fail(path, "cannot encode texture '" + t.name + "' as PNG");
            images.push_back(
                {{"name", t.name}, {"bufferView", bin.addView(png.data(), png.size(), 0)}, {"mimeType", "image/png"}});
            textures.push_back({{"source", int(images.size()) - 1}});
        }
        doc["images"] = images;
        doc["textures"] = textures;
    }

    if (!scene.lights.empty()) {
        json lights = json::array();
        for (const Light& l : scene.lights) {
            lights.push_back(lightJson(l));
            json node = frameNode(l.position, l.type == LightType::Point ? nullptr : &l.direction, nullptr);
            node["name"] = l.name;
            node["extensions"]["KHR_lights_punctual"] = {{"light", int(lights.size()) - 1}};
            nodes.push_back(node);
        }
        doc["extensions"]["KHR_lights_punctual"] = {{"lights", lights}};
        extensions.insert("KHR_lights_punctual");
    }

    const Camera& c = scene.camera;
    doc["cameras"] = json::array(
        {{{"name", "camera"},
          {"type", "perspective"},
          {"perspective", {{"yfov", decimal(c.yfovRad)}, {"znear", decimal(c.znear)}, {"zfar", decimal(c.zfar)}}}}});
    json cameraNode = frameNode(c.position, &c.forward, &c.up);
    cameraNode["name"] = "camera";
    cameraNode["camera"] = 0;
    nodes.push_back(cameraNode);

    doc["nodes"] = nodes;
    json roots = json::array();
    for (std::size_t i = 0; i < nodes.size(); ++i) roots.push_back(i);
    doc["scenes"] = json::array({{{"name", scene.name}, {"nodes", roots}}});
    doc["scene"] = 0;
    if (!extensions.empty()) doc["extensionsUsed"] = std::vector<std::string>(extensions.begin(), extensions.end());
    if (!bin.bytes.empty()) {
        bin.bytes.resize((bin.bytes.size() + 3) & ~std::size_t(3), '\0');
        doc["buffers"] = json::array({{{"uri", uriEscape(binName)}, {"byteLength", bin.bytes.size()}}});
        doc["bufferViews"] = bin.views;
        doc["accessors"] = bin.accessors;
    }

    try {
        // The .bin first: a .gltf on disk never names a .bin that is not there yet.
        if (!bin.bytes.empty()) writeFileAtomic(binPath.string(), bin.bytes);
        writeFileAtomic(path, doc.dump(2) + "\n");
    } catch (const ImageError& e) {
        throw SceneError(e.what());
    }
}

} // namespace bounce::core
