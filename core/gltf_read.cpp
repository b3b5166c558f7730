// Loading glTF into core::Scene (core/gltf_io.h says what is kept and what is refused): parse through
// the folder jail (core/gltf_files.h), decode base-colour textures, read materials, walk the node tree
// into world-space meshes, lights and one camera, and check the result.
#include "core/gltf_io.h"
#include "core/json_depth.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <set>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <stb_image.h> // implementation in Debian's libstb

#include "core/gltf_files.h"
#include "core/image.h"

namespace bounce::core {

namespace fs = std::filesystem;
using gltf::fail;
using gltf::FolderJail;
using gltf::lowerExtension;

namespace {

// No accessor of a scene this project renders comes near 2^28 elements; anything larger is a corrupt
// or hostile file, refused before any allocation.
constexpr std::uint64_t kMaxAccessorCount = std::uint64_t(1) << 28;
constexpr std::uint64_t kMaxTexturePixels = std::uint64_t(1) << 26; // 8k x 8k

constexpr int kModeTriangles = 4;

bool isIdentity(const glm::dmat4& m)
{
    return m == glm::dmat4(1.0);
}

// -0 and +0 mean the same direction; directions derived from node matrices are canonicalised so that a
// written and reloaded scene hashes the same as the original.
glm::vec3 withoutNegativeZero(glm::vec3 v)
{
    return v + glm::vec3(0.0f);
}

// Normalises only when the vector is measurably off unit length, so that unit vectors survive a round
// trip bit for bit.
glm::dvec3 unitIfNeeded(glm::dvec3 v)
{
    const double len2 = glm::dot(v, v);
    return std::abs(len2 - 1.0) > 1e-6 ? v / std::sqrt(len2) : v;
}

std::uint32_t be32(const unsigned char* p)
{
    return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3];
}

// The size a PNG (IHDR) or baseline/progressive JPEG (SOFn) header claims, read before stb_image sees
// it: stb refuses a header of 100000^2 pixels as "too large" and then, trying its other formats,
// reports "unknown image type". False when the bytes are neither.
bool claimedImageSize(const unsigned char* p, std::size_t size, std::uint64_t& w, std::uint64_t& h)
{
    static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (size >= 24 && std::memcmp(p, kPng, 8) == 0 && std::memcmp(p + 12, "IHDR", 4) == 0) {
        w = be32(p + 16);
        h = be32(p + 20);
        return true;
    }
    if (size < 4 || p[0] != 0xFF || p[1] != 0xD8) return false;
    for (std::size_t i = 2; i + 9 < size;) {
        if (p[i] != 0xFF) return false;
        const unsigned char marker = p[i + 1];
        const std::size_t length = std::size_t(p[i + 2]) << 8 | p[i + 3];
        if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC) {
            h = std::uint64_t(p[i + 5]) << 8 | p[i + 6];
            w = std::uint64_t(p[i + 7]) << 8 | p[i + 8];
            return true;
        }
        i += 2 + length;
    }
    return false;
}

class GltfReader {
public:
    explicit GltfReader(std::string path) : path_(std::move(path)) {}

    Scene read()
    {
        parse();
        loadTextures();
        loadMaterials();
        walkScene();
        finishCamera();
        if (const std::string problems = scene_.validate(); !problems.empty())
            fail(path_, "invalid scene data: " + trimmed(problems));
        return std::move(scene_);
    }

private:
    struct Node {
        int index;
        glm::dmat4 world;
        bool identity;
    };

    std::string path_;
    tinygltf::Model model_;
    Scene scene_;
    std::map<int, int> textureOfImage_;               // glTF image index -> Scene::textures index
    std::map<int, glm::dvec2> meanMetallicRoughness_; // glTF image index -> its mean metallic, roughness
    int defaultMaterial_ = -1;
    bool haveCamera_ = false;
    bool cameraHasZfar_ = false;

    void warn(const std::string& what) const { std::cerr << "warning: " << path_ << ": " << what << "\n"; }

    // ---- file level ---------------------------------------------------------------------------------

    std::vector<unsigned char> readFile() const
    {
        std::ifstream in(path_, std::ios::binary);
        if (!in) fail(path_, std::string("cannot open: ") + std::strerror(errno));
        std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (in.bad()) fail(path_, "read error");
        if (bytes.size() >= (std::uint64_t(1) << 32)) fail(path_, "file too large (4 GiB or more)");
        return bytes;
    }

    static std::uint32_t le32(const unsigned char* p)
    {
        return p[0] | (p[1] << 8) | (p[2] << 16) | (std::uint32_t(p[3]) << 24);
    }

    // tinygltf reports JSON syntax errors and GLB framing errors in its own words; checking them here
    // first gives messages that say what is wrong with the file.
    void checkFraming(const std::vector<unsigned char>& bytes, bool binary) const
    {
        const char* json = reinterpret_cast<const char*>(bytes.data());
        std::size_t jsonSize = bytes.size();
        if (binary) {
            if (bytes.size() < 20 || std::memcmp(bytes.data(), "glTF", 4) != 0)
                fail(path_, "not a GLB file (truncated or bad magic)");
            const std::uint32_t length = le32(&bytes[8]);
            const std::uint32_t chunkLength = le32(&bytes[12]);
            if (length > bytes.size())
                fail(path_, "GLB is truncated: header says " + std::to_string(length) + " bytes, file has " +
                                std::to_string(bytes.size()));
            if (std::uint64_t(chunkLength) + 20 > length || le32(&bytes[16]) != 0x4E4F534Au)
                fail(path_, "GLB is truncated or malformed: bad JSON chunk");
            json += 20;
            jsonSize = chunkLength;
        }
        if (!nlohmann::json::accept(json, json + jsonSize)) fail(path_, "malformed JSON (truncated or not glTF JSON)");
        if (const std::size_t depth = jsonNestingDepth(json, json + jsonSize); depth > kMaxGltfJsonDepth)
            fail(path_, "JSON nests " + std::to_string(depth) + " levels deep; more than " +
                            std::to_string(kMaxGltfJsonDepth) + " is refused (no glTF needs it)");
    }

    void parse()
    {
        const std::vector<unsigned char> bytes = readFile();
        const bool binary =
            lowerExtension(path_) == ".glb" || (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0);
        checkFraming(bytes, binary);

        std::error_code ec;
        const fs::path folder = fs::weakly_canonical(fs::absolute(path_, ec).parent_path(), ec);
        if (ec) fail(path_, "cannot resolve the scene's folder: " + ec.message());
        FolderJail jail;
        jail.prefix = folder.string();
        if (jail.prefix.empty() || jail.prefix.back() != '/') jail.prefix += '/';
        jail.model = &model_;

        tinygltf::TinyGLTF loader;
        loader.SetFsCallbacks(gltf::jailCallbacks(jail));
        loader.SetImageLoader(gltf::keepEncodedImage, &jail);
        std::string err, warnings;
        const std::string baseDir = jail.prefix.substr(0, jail.prefix.size() - 1);
        const bool ok =
            binary
                ? loader.LoadBinaryFromMemory(&model_, &err, &warnings, bytes.data(), unsigned(bytes.size()), baseDir)
                : loader.LoadASCIIFromString(&model_, &err, &warnings, reinterpret_cast<const char*>(bytes.data()),
                                             unsigned(bytes.size()), baseDir);
        if (!jail.notFiles.empty())
            fail(path_, "URI '" + jail.notFiles.front() +
                            "' names a folder or nothing, not a file (a buffer or image needs a file name)");
        if (!jail.refused.empty())
            fail(path_,
                 "URI '" + jail.refused.front() + "' leaves the scene's folder (absolute or '..' path); refused");
        if (!ok) {
            if (!jail.missing.empty())
                fail(path_, "missing file '" + jail.missing.front() + "' (a buffer or image it refers to)");
            fail(path_, "invalid glTF: " + trimmed(err));
        }
        for (std::size_t i = 0; i < model_.images.size(); ++i)
            if (model_.images[i].image.empty())
                fail(path_, "image " + std::to_string(i) + " ('" + model_.images[i].uri + "') is missing or empty");
    }

    static std::string trimmed(std::string s)
    {
        while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
        for (std::size_t i = s.find('\n'); i != std::string::npos; i = s.find('\n', i)) s.replace(i, 1, "; ");
        return s;
    }

    // ---- accessors ----------------------------------------------------------------------------------

    struct View {
        const unsigned char* data = nullptr;
        std::size_t stride = 0;
        std::size_t count = 0;
        int componentType = 0;
        int components = 0;
        bool normalized = false;
    };

    static int componentSize(int type)
    {
        switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
        }
    }

    View view(int accessorIndex, int expectedType, const std::string& what) const
    {
        const std::string where = what + " accessor " + std::to_string(accessorIndex);
        if (accessorIndex < 0 || std::size_t(accessorIndex) >= model_.accessors.size())
            fail(path_, where + " is out of range (" + std::to_string(model_.accessors.size()) + " accessors)");
        const tinygltf::Accessor& a = model_.accessors[std::size_t(accessorIndex)];
        if (a.sparse.isSparse) fail(path_, where + ": sparse accessors are not supported");
        if (a.type != expectedType) fail(path_, where + " has the wrong type for " + what);
        if (a.count > kMaxAccessorCount)
            fail(path_, where + ": count " + std::to_string(a.count) + " exceeds the limit of 2^28 elements");
        View v;
        v.count = a.count;
        v.componentType = a.componentType;
        v.components = tinygltf::GetNumComponentsInType(std::uint32_t(a.type));
        v.normalized = a.normalized;
        const int size = componentSize(a.componentType);
        if (size == 0) fail(path_, where + ": unsupported component type " + std::to_string(a.componentType));
        const std::uint64_t elementSize = std::uint64_t(size) * std::uint64_t(v.components);
        // Without bufferView (and without sparse data) an accessor is all zeros: no use for geometry, and
        // its count would not be bounded by any data in the file.
        if (a.bufferView < 0) fail(path_, where + " has no bufferView (all zeros); not supported");

        if (std::size_t(a.bufferView) >= model_.bufferViews.size())
            fail(path_, where + ": bufferView " + std::to_string(a.bufferView) + " is out of range");
        const tinygltf::BufferView& bv = model_.bufferViews[std::size_t(a.bufferView)];
        if (bv.buffer < 0 || std::size_t(bv.buffer) >= model_.buffers.size())
            fail(path_, where + ": buffer " + std::to_string(bv.buffer) + " is out of range");
        const std::vector<unsigned char>& buffer = model_.buffers[std::size_t(bv.buffer)].data;
        if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset)
            fail(path_, where + ": bufferView " + std::to_string(a.bufferView) + " (offset " +
                            std::to_string(bv.byteOffset) + ", length " + std::to_string(bv.byteLength) +
                            ") extends beyond the end of buffer " + std::to_string(bv.buffer) + " (" +
                            std::to_string(buffer.size()) + " bytes)");
        v.stride = bv.byteStride != 0 ? bv.byteStride : std::size_t(elementSize);
        if (v.stride < elementSize)
            fail(path_, where + ": byteStride " + std::to_string(v.stride) + " is smaller than an element");
        // Overflow-free: count <= 2^28 and stride <= 252 (tinygltf checks the latter).
        const std::uint64_t needed =
            a.count == 0 ? 0 : std::uint64_t(a.byteOffset) + (a.count - 1) * std::uint64_t(v.stride) + elementSize;
        if (a.byteOffset > bv.byteLength || needed > bv.byteLength)
            fail(path_, where + ": offset " + std::to_string(a.byteOffset) + " + count " + std::to_string(a.count) +
                            " x stride " + std::to_string(v.stride) + " extends beyond the end of bufferView " +
                            std::to_string(a.bufferView) + " (" + std::to_string(bv.byteLength) + " bytes)");
        v.data = buffer.data() + bv.byteOffset + a.byteOffset;
        return v;
    }

    static double component(const View& v, std::size_t i, int c)
    {
        const unsigned char* p = v.data + i * v.stride + std::size_t(c) * std::size_t(componentSize(v.componentType));
        auto load = [p](auto value) {
            std::memcpy(&value, p, sizeof value);
            return value;
        };
        switch (v.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return load(float());
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return v.normalized ? load(std::uint8_t()) / 255.0 : load(std::uint8_t());
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return v.normalized ? load(std::uint16_t()) / 65535.0 : load(std::uint16_t());
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load(std::uint32_t());
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return v.normalized ? std::max(load(std::int8_t()) / 127.0, -1.0) : load(std::int8_t());
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return v.normalized ? std::max(load(std::int16_t()) / 32767.0, -1.0) : load(std::int16_t());
        default: return 0.0;
        }
    }

    template <int N>
    std::vector<glm::vec<N, float>> readVectors(int accessorIndex, const std::string& what) const
    {
        const View v = view(accessorIndex,
                            N == 2   ? TINYGLTF_TYPE_VEC2
                            : N == 3 ? TINYGLTF_TYPE_VEC3
                                     : TINYGLTF_TYPE_VEC4,
                            what);
        std::vector<glm::vec<N, float>> out(v.count);
        for (std::size_t i = 0; i < v.count; ++i)
            for (int c = 0; c < N; ++c) out[i][c] = float(component(v, i, c));
        return out;
    }

    std::vector<std::uint32_t> readIndices(int accessorIndex) const
    {
        // The component type first: a float index accessor is wrong in kind, whatever its byte range says.
        if (accessorIndex >= 0 && std::size_t(accessorIndex) < model_.accessors.size()) {
            const int type = model_.accessors[std::size_t(accessorIndex)].componentType;
            if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                fail(path_, "indices accessor " + std::to_string(accessorIndex) + ": component type " +
                                std::to_string(type) + (type == TINYGLTF_COMPONENT_TYPE_FLOAT ? " (float)" : "") +
                                " is not an unsigned integer type (5121, 5123 or 5125, as glTF requires)");
        }
        const View v = view(accessorIndex, TINYGLTF_TYPE_SCALAR, "indices");
        std::vector<std::uint32_t> out(v.count);
        for (std::size_t i = 0; i < v.count; ++i) out[i] = std::uint32_t(component(v, i, 0));
        return out;
    }

    // ---- textures and materials ---------------------------------------------------------------------

    void loadTextures()
    {
        // Scene textures follow the order of the glTF images that serve as base colour or normal map, so
        // that a written scene (one image per texture) loads back with the same indices.
        std::set<int> used;
        for (const tinygltf::Material& m : model_.materials) {
            if (const int t = m.pbrMetallicRoughness.baseColorTexture.index; t >= 0) used.insert(imageOfTexture(t));
            if (const int t = m.normalTexture.index; t >= 0) used.insert(imageOfTexture(t));
        }
        used.erase(-1);
        for (int image : used) {
            textureOfImage_[image] = int(scene_.textures.size());
            scene_.textures.push_back(decode(image));
        }
    }

    int imageOfTexture(int textureIndex) const
    {
        if (std::size_t(textureIndex) >= model_.textures.size())
            fail(path_, "texture " + std::to_string(textureIndex) + " is out of range");
        const int source = model_.textures[std::size_t(textureIndex)].source;
        if (source < 0) {
            warn("texture " + std::to_string(textureIndex) + " has no image source it can read; ignored");
            return -1;
        }
        if (std::size_t(source) >= model_.images.size())
            fail(path_, "image " + std::to_string(source) + " is out of range");
        return source;
    }

    Texture decode(int imageIndex) const
    {
        const tinygltf::Image& image = model_.images[std::size_t(imageIndex)];
        const std::string where =
            "image " + std::to_string(imageIndex) + " ('" + (image.uri.empty() ? image.name : image.uri) + "')";
        const auto* bytes = image.image.data();
        const int size = int(image.image.size());
        std::uint64_t claimedW = 0, claimedH = 0;
        if (claimedImageSize(bytes, image.image.size(), claimedW, claimedH) &&
            (claimedW == 0 || claimedH == 0 || claimedW * claimedH > kMaxTexturePixels))
            fail(path_, where + ": its header claims " + std::to_string(claimedW) + "x" + std::to_string(claimedH) +
                            " pixels; textures of more than 2^26 pixels (8192 x 8192) or of none are refused");
        int w = 0, h = 0, channels = 0;
        if (!stbi_info_from_memory(bytes, size, &w, &h, &channels))
            fail(path_, where + " cannot be decoded: " + stbi_failure_reason());
        if (w <= 0 || h <= 0 || std::uint64_t(w) * std::uint64_t(h) > kMaxTexturePixels)
            fail(path_, where + " has unusable size " + std::to_string(w) + "x" + std::to_string(h));
        unsigned char* pixels = stbi_load_from_memory(bytes, size, &w, &h, &channels, 4);
        if (!pixels) fail(path_, where + " cannot be decoded: " + stbi_failure_reason());
        Texture t;
        t.name = image.name.empty() ? image.uri : image.name;
        t.width = w;
        t.height = h;
        t.rgba8.assign(pixels, pixels + std::size_t(w) * std::size_t(h) * 4);
        stbi_image_free(pixels);
        return t;
    }

    // The mean metallic (blue) and roughness (green) of a metallicRoughness image, linear 0..1.
    glm::dvec2 meanMetallicRoughness(int imageIndex)
    {
        if (const auto it = meanMetallicRoughness_.find(imageIndex); it != meanMetallicRoughness_.end())
            return it->second;
        const Texture t = decode(imageIndex);
        glm::dvec2 sum(0.0);
        for (std::size_t p = 0; p + 3 < t.rgba8.size(); p += 4) sum += glm::dvec2(t.rgba8[p + 2], t.rgba8[p + 1]);
        const glm::dvec2 mean = sum / (255.0 * double(std::max<std::size_t>(t.rgba8.size() / 4, 1)));
        meanMetallicRoughness_[imageIndex] = mean;
        return mean;
    }

    static double number(const tinygltf::Value& object, const char* key, double fallback)
    {
        if (!object.Has(key) || !object.Get(key).IsNumber()) return fallback;
        return object.Get(key).GetNumberAsDouble();
    }

    static glm::dvec3 colour(const tinygltf::Value& object, const char* key, glm::dvec3 fallback)
    {
        if (!object.Has(key)) return fallback;
        const tinygltf::Value& a = object.Get(key);
        if (!a.IsArray() || a.ArrayLen() != 3) return fallback;
        glm::dvec3 c;
        for (int i = 0; i < 3; ++i) c[i] = a.Get(i).IsNumber() ? a.Get(i).GetNumberAsDouble() : fallback[i];
        return c;
    }

    static const tinygltf::Value* extension(const tinygltf::ExtensionMap& map, const char* name)
    {
        const auto it = map.find(name);
        return it != map.end() && it->second.IsObject() ? &it->second : nullptr;
    }

    void loadMaterials()
    {
        for (const tinygltf::Material& gm : model_.materials) {
            Material m;
            m.name = gm.name;
            const tinygltf::PbrMetallicRoughness& pbr = gm.pbrMetallicRoughness;
            if (pbr.baseColorFactor.size() == 4) {
                m.baseColor = glm::vec3(float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]),
                                        float(pbr.baseColorFactor[2]));
                m.baseAlpha = float(pbr.baseColorFactor[3]);
            }
            if (pbr.baseColorTexture.index >= 0) {
                if (pbr.baseColorTexture.texCoord != 0) warn("material '" + gm.name + "': only TEXCOORD_0 is read");
                const auto it = textureOfImage_.find(imageOfTexture(pbr.baseColorTexture.index));
                if (it != textureOfImage_.end()) m.baseColorTexture = it->second;
            }
            m.metallic = float(pbr.metallicFactor);
            m.roughness = float(pbr.roughnessFactor);
            if (pbr.metallicRoughnessTexture.index >= 0) {
                // No per-texel metallic or roughness in Bounce: the texture's mean multiplies the factors.
                // Ignoring it would leave metallicFactor's default of 1, a mirror-like metal where the
                // texture says stone (Crytek Sponza).
                if (const int image = imageOfTexture(pbr.metallicRoughnessTexture.index); image >= 0) {
                    const glm::dvec2 mean = meanMetallicRoughness(image);
                    m.metallic = float(pbr.metallicFactor * mean.x);
                    m.roughness = float(pbr.roughnessFactor * mean.y);
                }
            }
            double strength = 1.0;
            if (const tinygltf::Value* e = extension(gm.extensions, "KHR_materials_emissive_strength"))
                strength = number(*e, "emissiveStrength", 1.0);
            if (gm.emissiveFactor.size() == 3)
                // The product is formed in double and rounded once, so that writeGltf's split of an
                // emission into factor x strength comes back bit for bit.
                m.emission =
                    glm::vec3(glm::dvec3(gm.emissiveFactor[0], gm.emissiveFactor[1], gm.emissiveFactor[2]) * strength);
            if (const tinygltf::Value* s = extension(gm.extensions, "KHR_materials_specular")) {
                m.specular = float(number(*s, "specularFactor", 1.0));
                m.specularColor = glm::vec3(colour(*s, "specularColorFactor", glm::dvec3(1.0)));
            }
            m.doubleSided = gm.doubleSided;
            readAlphaMode(gm, m);
            readNormalTexture(gm, m);
            scene_.materials.push_back(m);
        }
    }

    void readNormalTexture(const tinygltf::Material& gm, Material& m)
    {
        if (gm.normalTexture.index < 0) return;
        if (gm.normalTexture.texCoord != 0) {
            warn("material '" + gm.name + "': its normal texture reads TEXCOORD_" +
                 std::to_string(gm.normalTexture.texCoord) + ", and only TEXCOORD_0 is read; the map is ignored");
            return;
        }
        const auto it = textureOfImage_.find(imageOfTexture(gm.normalTexture.index));
        if (it == textureOfImage_.end()) return;
        m.normalTexture = it->second;
        m.normalScale = float(gm.normalTexture.scale);
        if (!std::isfinite(m.normalScale))
            fail(path_, "material '" + gm.name + "': normal texture scale is not finite");
    }

    // MASK cuts holes wherever alpha < alphaCutoff; BLEND (translucency) has no model in Bounce.
    void readAlphaMode(const tinygltf::Material& gm, Material& m) const
    {
        if (gm.alphaMode == "MASK") {
            m.alphaMode = AlphaMode::Mask;
            m.alphaCutoff = float(gm.alphaCutoff);
        } else if (gm.alphaMode != "OPAQUE") {
            warn("material '" + gm.name + "': alphaMode '" + gm.alphaMode + "' is drawn OPAQUE");
        }
    }

    std::uint32_t materialFor(int index)
    {
        if (index >= 0) {
            if (std::size_t(index) >= model_.materials.size())
                fail(path_, "material " + std::to_string(index) + " is out of range (" +
                                std::to_string(model_.materials.size()) + " materials)");
            return std::uint32_t(index);
        }
        if (defaultMaterial_ < 0) {
            // glTF's default material: base colour 1, metallic 1, roughness 1, no emission.
            Material m;
            m.name = "glTF default";
            m.metallic = 1.0f;
            defaultMaterial_ = int(scene_.materials.size());
            scene_.materials.push_back(m);
        }
        return std::uint32_t(defaultMaterial_);
    }

    // ---- node hierarchy -----------------------------------------------------------------------------

    glm::dmat4 localMatrix(const tinygltf::Node& n, int index) const
    {
        const std::string where = "node " + std::to_string(index);
        if (!n.matrix.empty()) {
            if (n.matrix.size() != 16) fail(path_, where + ": matrix must have 16 numbers");
            glm::dmat4 m;
            for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = n.matrix[std::size_t(i)]; // column-major
            return m;
        }
        if ((!n.translation.empty() && n.translation.size() != 3) || (!n.rotation.empty() && n.rotation.size() != 4) ||
            (!n.scale.empty() && n.scale.size() != 3))
            fail(path_, where + ": translation/rotation/scale have the wrong number of components");
        glm::dmat3 r(1.0);
        if (!n.rotation.empty()) {
            glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]); // glTF stores x, y, z, w
            if (std::abs(glm::dot(q, q) - 1.0) > 1e-6) q = glm::normalize(q);
            r = glm::mat3_cast(q);
        }
        glm::dmat4 m(1.0);
        for (int c = 0; c < 3; ++c) m[c] = glm::dvec4(n.scale.empty() ? r[c] : r[c] * n.scale[std::size_t(c)], 0.0);
        if (!n.translation.empty()) m[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
        return m;
    }

    std::vector<int> rootNodes()
    {
        std::vector<int> roots;
        if (!model_.scenes.empty()) {
            const int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
            if (std::size_t(s) >= model_.scenes.size())
                fail(path_, "default scene " + std::to_string(s) + " is out of range");
            scene_.name = model_.scenes[std::size_t(s)].name;
            return model_.scenes[std::size_t(s)].nodes;
        }
        // No scene: every node that is nobody's child is a root.
        std::vector<bool> isChild(model_.nodes.size(), false);
        for (const tinygltf::Node& n : model_.nodes)
            for (int c : n.children)
                if (c >= 0 && std::size_t(c) < isChild.size()) isChild[std::size_t(c)] = true;
        for (std::size_t i = 0; i < isChild.size(); ++i)
            if (!isChild[i]) roots.push_back(int(i));
        return roots;
    }

    void walkScene()
    {
        const std::vector<int> roots = rootNodes();
        if (scene_.name.empty()) scene_.name = fs::path(path_).stem().string();
        // An explicit stack (the hierarchy may be deep) and a visited mark (it may be cyclic).
        std::vector<bool> visited(model_.nodes.size(), false);
        std::vector<Node> stack;
        for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::dmat4(1.0), true});
        while (!stack.empty()) {
            const Node parent = stack.back();
            stack.pop_back();
            if (parent.index < 0 || std::size_t(parent.index) >= model_.nodes.size())
                fail(path_, "node " + std::to_string(parent.index) + " is out of range (" +
                                std::to_string(model_.nodes.size()) + " nodes)");
            if (visited[std::size_t(parent.index)])
                fail(path_, "node " + std::to_string(parent.index) +
                                " is reached twice: the node hierarchy has a cycle or a shared child");
            visited[std::size_t(parent.index)] = true;
            const tinygltf::Node& n = model_.nodes[std::size_t(parent.index)];
            const glm::dmat4 local = localMatrix(n, parent.index);
            Node node{parent.index, parent.world, parent.identity};
            if (!isIdentity(local)) {
                node.world = parent.identity ? local : parent.world * local;
                node.identity = false;
            }
            visitNode(n, node);
            for (auto c = n.children.rbegin(); c != n.children.rend(); ++c)
                stack.push_back({*c, node.world, node.identity});
        }
        // Without a scene every node is drawn; one that no walk from a root reached lies on a cycle (each
        // node of a cycle is somebody's child, so none of them is a root).
        if (model_.scenes.empty())
            for (std::size_t i = 0; i < visited.size(); ++i)
                if (!visited[i])
                    fail(path_, "node " + std::to_string(i) +
                                    " lies on a cycle of the node hierarchy (the file has no scene, so every node is "
                                    "drawn, and this one has no root)");
    }

    void visitNode(const tinygltf::Node& n, const Node& node)
    {
        if (n.mesh >= 0) {
            if (std::size_t(n.mesh) >= model_.meshes.size())
                fail(path_, "mesh " + std::to_string(n.mesh) + " is out of range");
            const tinygltf::Mesh& mesh = model_.meshes[std::size_t(n.mesh)];
            for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
                const std::string name = mesh.primitives.size() == 1 ? mesh.name : mesh.name + "/" + std::to_string(p);
                const std::string where = "mesh " + std::to_string(n.mesh) +
                                          (mesh.name.empty() ? "" : " ('" + mesh.name + "')") + " primitive " +
                                          std::to_string(p);
                addPrimitive(mesh.primitives[p], name, where, node);
            }
        }
        if (n.camera >= 0) {
            if (std::size_t(n.camera) >= model_.cameras.size())
                fail(path_, "camera " + std::to_string(n.camera) + " is out of range");
            addCamera(model_.cameras[std::size_t(n.camera)], node);
        }
        if (const tinygltf::Value* e = extension(n.extensions, "KHR_lights_punctual")) {
            const double index = number(*e, "light", -1.0);
            if (index != std::floor(index))
                fail(path_, "node light index " + std::to_string(index) + " is not a whole number");
            if (!(index >= 0.0 && index < double(model_.lights.size())))
                fail(path_, "light " + std::to_string(std::llround(std::clamp(index, -1.0, 1e15))) +
                                " is out of range (" + std::to_string(model_.lights.size()) + " lights)");
            addLight(model_.lights[std::size_t(index)], node);
        }
    }

    // ---- primitives, lights, camera -----------------------------------------------------------------

    void addPrimitive(const tinygltf::Primitive& p, const std::string& name, const std::string& where, const Node& node)
    {
        if (p.mode != -1 && p.mode != kModeTriangles) {
            warn(where + ": primitive mode " + std::to_string(p.mode) + " is not TRIANGLES; skipped");
            return;
        }
        const auto attribute = [&p](const char* key) {
            const auto it = p.attributes.find(key);
            return it == p.attributes.end() ? -1 : it->second;
        };
        if (attribute("POSITION") < 0) {
            warn(where + ": primitive without POSITION; skipped");
            return;
        }
        Mesh m;
        m.name = name;
        m.material = materialFor(p.material);
        m.positions = readVectors<3>(attribute("POSITION"), "POSITION");
        if (attribute("NORMAL") >= 0) m.normals = readVectors<3>(attribute("NORMAL"), "NORMAL");
        if (attribute("TEXCOORD_0") >= 0) m.uvs = readVectors<2>(attribute("TEXCOORD_0"), "TEXCOORD_0");
        // Tangents matter only under a normal map; elsewhere they are not read (nor hashed, nor uploaded).
        const bool mapped = scene_.materials[m.material].hasNormalMap();
        if (mapped && attribute("TANGENT") >= 0) m.tangents = readVectors<4>(attribute("TANGENT"), "TANGENT");
        if (!m.tangents.empty() && m.tangents.size() != m.positions.size())
            fail(path_, where + ": TANGENT and POSITION counts differ");
        if (!m.normals.empty() && m.normals.size() != m.positions.size())
            fail(path_, where + ": NORMAL and POSITION counts differ");
        if (!m.uvs.empty() && m.uvs.size() != m.positions.size())
            fail(path_, where + ": TEXCOORD_0 and POSITION counts differ");
        if (p.indices >= 0) {
            m.indices = readIndices(p.indices);
            for (std::uint32_t i : m.indices)
                if (i >= m.positions.size())
                    fail(path_, where + ": index " + std::to_string(i) + " is out of range (" +
                                    std::to_string(m.positions.size()) + " vertices)");
        } else {
            m.indices.resize(m.positions.size());
            for (std::size_t i = 0; i < m.indices.size(); ++i) m.indices[i] = std::uint32_t(i);
        }
        if (m.indices.size() % 3 != 0)
            fail(path_,
                 where + ": " + std::to_string(m.indices.size()) + " indices is not a whole number of triangles");

        if (!node.identity) toWorld(m, node.world);
        for (glm::vec3& n : m.normals) n = glm::vec3(unitIfNeeded(glm::dvec3(n))); // files may store them unnormalised
        const bool normalsUsable = std::all_of(m.normals.begin(), m.normals.end(), [](const glm::vec3& n) {
            const float len2 = glm::dot(n, n);
            return std::isfinite(len2) && len2 > 1e-12f;
        });
        if (!normalsUsable) warn(where + ": zero or non-finite normals; flat normals generated instead");
        if (m.normals.empty() || !normalsUsable) makeFlat(m);
        if (mapped) readyTangents(m, where);
        if (m.indices.empty()) return;
        scene_.meshes.push_back(std::move(m));
    }

    static void toWorld(Mesh& m, const glm::dmat4& world)
    {
        for (glm::vec3& p : m.positions) p = glm::vec3(world * glm::dvec4(p, 1.0));
        const glm::dmat3 normalMatrix = glm::inverseTranspose(glm::dmat3(world));
        for (glm::vec3& n : m.normals) n = glm::vec3(normalMatrix * glm::dvec3(n));
        // Tangents lie in the surface: they move with the model matrix, not the normals' inverse transpose.
        // A mirroring transform flips the cross product of normal and tangent, so the handedness flips with
        // it, and the bitangent keeps pointing where the image's +y does.
        const bool mirrors = glm::determinant(glm::dmat3(world)) < 0.0;
        for (glm::vec4& t : m.tangents)
            t = glm::vec4(glm::vec3(glm::dmat3(world) * glm::dvec3(t)), mirrors ? -t.w : t.w);
        // A mirroring transform turns counter-clockwise triangles clockwise; swap two corners back.
        if (mirrors)
            for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
    }

    // The tangents of a normal-mapped mesh: the file's, made unit with a handedness of +-1; where the file
    // has none, or one that is zero or not finite, computed from the uvs; without uvs, none (the mesh
    // shades with its vertex normals), with a warning each.
    void readyTangents(Mesh& m, const std::string& where) const
    {
        bool usable = !m.tangents.empty();
        for (glm::vec4& t : m.tangents) {
            const glm::dvec3 xyz(t);
            const double len2 = glm::dot(xyz, xyz);
            if (!(std::isfinite(len2) && len2 > 1e-12 && std::isfinite(t.w))) {
                usable = false;
                break;
            }
            t = glm::vec4(glm::vec3(unitIfNeeded(xyz)), t.w < 0.0f ? -1.0f : 1.0f);
        }
        if (usable) return;
        const bool had = !m.tangents.empty();
        m.tangents.clear();
        if (m.uvs.empty()) {
            warn(where + ": a normal map without TEXCOORD_0; the mesh shades with its vertex normals");
            return;
        }
        m.tangents = tangentsFromUvs(m);
        warn(where + (had ? ": zero or non-finite tangents" : ": no TANGENT") +
             "; tangents computed from TEXCOORD_0 (each vertex's sum over its triangles, not MikkTSpace: across "
             "uv seams they may differ from the authoring tool's)");
    }

    // glTF: without normals, flat normals. Each triangle gets its own three vertices.
    static void makeFlat(Mesh& m)
    {
        Mesh flat;
        flat.name = m.name;
        flat.material = m.material;
        for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]),
                c(m.positions[m.indices[t + 2]]);
            const glm::dvec3 cross = glm::cross(b - a, c - a);
            const double len = glm::length(cross);
            // A degenerate triangle covers no area; any unit normal will do.
            const glm::vec3 n =
                len > 0.0 && std::isfinite(len) ? withoutNegativeZero(glm::vec3(cross / len)) : glm::vec3(0, 1, 0);
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t i = m.indices[t + std::size_t(k)];
                flat.indices.push_back(std::uint32_t(flat.positions.size()));
                flat.positions.push_back(m.positions[i]);
                flat.normals.push_back(n);
                if (!m.uvs.empty()) flat.uvs.push_back(m.uvs[i]);
                if (!m.tangents.empty()) flat.tangents.push_back(m.tangents[i]);
            }
        }
        m = std::move(flat);
    }

    void addLight(const tinygltf::Light& gl, const Node& node)
    {
        Light l;
        l.name = gl.name;
        if (gl.type == "point")
            l.type = LightType::Point;
        else if (gl.type == "spot")
            l.type = LightType::Spot;
        else if (gl.type == "directional")
            l.type = LightType::Directional;
        else {
            warn("light '" + gl.name + "' has unknown type '" + gl.type + "'; skipped");
            return;
        }
        const glm::dvec3 colour =
            gl.color.size() == 3 ? glm::dvec3(gl.color[0], gl.color[1], gl.color[2]) : glm::dvec3(1.0);
        checkLight(gl, colour);
        l.intensity = glm::vec3(colour * gl.intensity); // W/sr (W/m^2 directional), rounded once
        l.position = glm::vec3(node.world[3]);
        if (l.type != LightType::Point)
            l.direction = withoutNegativeZero(glm::vec3(unitIfNeeded(-glm::dvec3(node.world[2]))));
        if (l.type == LightType::Spot) {
            l.innerConeRad = float(gl.spot.innerConeAngle);
            l.outerConeRad = float(gl.spot.outerConeAngle);
        }
        scene_.lights.push_back(l);
    }

    // What KHR_lights_punctual forbids, refused rather than clamped: the rasteriser and the path tracer
    // would otherwise disagree (a negative intensity is black in one and negative radiance in the other).
    void checkLight(const tinygltf::Light& gl, const glm::dvec3& colour) const
    {
        const std::string where = "light '" + gl.name + "'";
        if (!(gl.intensity >= 0.0))
            fail(path_, where + ": intensity " + std::to_string(gl.intensity) + " is negative (or not a number)");
        if (!(colour.x >= 0.0 && colour.y >= 0.0 && colour.z >= 0.0))
            fail(path_, where + ": a colour component is negative");
        if (gl.type != "spot") return;
        // A float pi/2 written as a double lies just above the double pi/2: allow a float's rounding.
        const double inner = gl.spot.innerConeAngle, outer = gl.spot.outerConeAngle,
                     quarter = 0.5 * std::numbers::pi + 1e-6;
        if (!(inner >= 0.0 && inner < outer && outer <= quarter))
            fail(path_, where + ": spot cone inner " + std::to_string(inner) + ", outer " + std::to_string(outer) +
                            " rad; glTF requires 0 <= innerConeAngle < outerConeAngle <= pi/2");
    }

    void addCamera(const tinygltf::Camera& c, const Node& node)
    {
        if (haveCamera_) return;
        if (c.type != "perspective") {
            warn("camera '" + c.name + "' is not perspective; ignored");
            return;
        }
        const tinygltf::PerspectiveCamera& pc = c.perspective;
        const std::string where = "camera '" + c.name + "'";
        if (!(pc.yfov > 0.0 && pc.yfov < std::numbers::pi))
            fail(path_, where + ": yfov " + std::to_string(pc.yfov) + " rad is outside (0, pi)");
        if (!(pc.znear > 0.0)) fail(path_, where + ": znear " + std::to_string(pc.znear) + " is not positive");
        // tinygltf reads an absent zfar (an infinite projection) as 0.
        if (pc.zfar != 0.0 && !(pc.zfar > pc.znear))
            fail(path_,
                 where + ": zfar " + std::to_string(pc.zfar) + " is not beyond znear " + std::to_string(pc.znear));
        haveCamera_ = true;
        Camera& cam = scene_.camera;
        cam.position = glm::vec3(node.world[3]);
        const glm::dvec3 forward = unitIfNeeded(-glm::dvec3(node.world[2]));
        glm::dvec3 up(node.world[1]);
        // A sheared node leaves +y not quite orthogonal to -z; Camera wants them orthogonal.
        if (std::abs(glm::dot(up, forward)) > 1e-6) up -= glm::dot(up, forward) * forward;
        cam.forward = withoutNegativeZero(glm::vec3(forward));
        cam.up = withoutNegativeZero(glm::vec3(unitIfNeeded(up)));
        cam.yfovRad = float(c.perspective.yfov);
        cam.znear = float(c.perspective.znear);
        cameraHasZfar_ = c.perspective.zfar > 0.0;
        if (cameraHasZfar_) cam.zfar = float(c.perspective.zfar);
    }

    static float farthestCorner(const glm::vec3& from, const Bounds& b)
    {
        float far = 0.0f;
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 corner((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z);
            far = std::max(far, glm::length(corner - from));
        }
        return far;
    }

    void finishCamera()
    {
        const Bounds b = scene_.bounds();
        Camera& cam = scene_.camera;
        scene_.cameraSource = haveCamera_ ? "glTF" : "framed the bounds (the glTF has no camera)";
        if (!haveCamera_) {
            cam = Camera{};
            if (!b.empty()) {
                // Back off along -z until the front face of the bounds fills the field of view.
                const glm::vec3 e = b.extent();
                const float half = std::max({0.5f * e.x, 0.5f * e.y, 1e-3f});
                const float distance = half / std::tan(0.5f * cam.yfovRad);
                cam.position = glm::vec3(b.centre().x, b.centre().y, b.lo.z - distance);
                cam.znear = std::max(1e-4f, 0.01f * distance);
            }
        }
        if ((!haveCamera_ || !cameraHasZfar_) && !b.empty())
            cam.zfar = std::max(2.0f * farthestCorner(cam.position, b), 10.0f * cam.znear);
    }
};

} // namespace

Scene loadGltf(const std::string& path)
{
    return GltfReader(path).read();
}

} // namespace bounce::core
