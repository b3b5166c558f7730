#include "gl/frame/gpu_scene.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdio>

#include "core/adjacency.h"
#include "gl/frame/bindings.h"
#include "gl/gl.h"

namespace bounce::gl {

namespace {

// The largest side of the normal maps' array (16 MiB a layer).
constexpr int kMaxNormalMapSize = 2048;

// 8-bit texels resampled (a box filter of the encoded bytes, or nearest when enlarging) to size x size.
void resampleInto(const core::Texture& t, int size, std::uint8_t* out)
{
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const int x0 = x * t.width / size, x1 = std::max(x0 + 1, (x + 1) * t.width / size);
            const int y0 = y * t.height / size, y1 = std::max(y0 + 1, (y + 1) * t.height / size);
            unsigned sum[4] = {0, 0, 0, 0};
            for (int sy = y0; sy < y1; ++sy)
                for (int sx = x0; sx < x1; ++sx)
                    for (int c = 0; c < 4; ++c) sum[c] += t.rgba8[(std::size_t(sy) * t.width + sx) * 4 + c];
            const unsigned n = unsigned((x1 - x0) * (y1 - y0));
            for (int c = 0; c < 4; ++c) out[(std::size_t(y) * size + x) * 4 + c] = std::uint8_t(sum[c] / n);
        }
}

} // namespace

GpuScene::GpuScene(const core::Scene& scene, int textureSize)
    : vao_("scene"), hasNormalMaps_(scene.hasNormalMaps()), hasAlphaMask_(scene.hasAlphaMask()), bounds_(scene.bounds())
{
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices;
    std::vector<glm::vec4> tangents; // with normal maps only: one per vertex, zero where a mesh has none
    vertices.reserve(scene.triangleCount() * 3);
    int lightCount = 0;
    bool warned = false;
    for (std::size_t mi = 0; mi < scene.meshes.size(); ++mi) {
        const core::Mesh& m = scene.meshes[mi];
        const auto base = std::uint32_t(vertices.size());
        for (std::size_t i = 0; i < m.positions.size(); ++i)
            vertices.push_back({m.positions[i], m.normals[i], m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[i], m.material});
        if (hasNormalMaps_) {
            const bool mapped = !m.tangents.empty() && !m.uvs.empty();
            for (std::size_t i = 0; i < m.positions.size(); ++i)
                tangents.push_back(mapped ? m.tangents[i] : glm::vec4(0.0f));
        }
        for (std::uint32_t idx : m.indices) indices.push_back(base + idx);

        // Every emitting triangle is an area light (up to kMaxAreaTriangles); those of one mesh share a
        // shadow cube. placeEmitters() puts them where the vertices are.
        const core::Material& mat = scene.materials[m.material];
        if (!mat.isEmissive()) continue;
        const double luminance = 0.2126 * mat.emission.x + 0.7152 * mat.emission.y + 0.0722 * mat.emission.z;
        const auto first = std::uint32_t((indices.size() - m.indices.size()) / 3);
        for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            Emitter e;
            e.triangle = first + std::uint32_t(t / 3);
            e.material = m.material;
            for (int k = 0; k < 3; ++k) e.corners[k] = base + m.indices[t + k];
            e.emission = mat.emission;
            e.luminance = luminance;
            e.group = int(mi);
            const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                            c = m.positions[m.indices[t + 2]];
            if (glm::length(glm::cross(b - a, c - a)) <= 0.0f) continue; // degenerate: emits nothing
            e.light = lightCount < kMaxAreaTriangles;
            if (e.light)
                ++lightCount;
            else if (!warned) {
                std::fprintf(stderr, "bounce: more than %d emissive triangles; the rest light nothing directly\n",
                             kMaxAreaTriangles);
                warned = true;
            }
            emitters_.push_back(e);
        }
    }

    if (hasAlphaMask_) {
        std::size_t first = 0;
        for (const core::Mesh& m : scene.meshes) {
            (scene.materials[m.material].isMasked() ? maskedRanges_ : opaqueRanges_).add(first, m.indices.size());
            first += m.indices.size();
        }
    }

    vertices_ = Buffer::fromVector("scene.vertices", vertices);
    indices_ = Buffer::fromVector("scene.indices", indices);
    indexCount_ = indices.size();
    glVertexArrayVertexBuffer(vao_.id(), 0, vertices_.id(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao_.id(), indices_.id());
    const struct {
        unsigned loc;
        int size;
        unsigned type;
        std::size_t offset;
    } attribs[] = {
        {0, 3, GL_FLOAT, offsetof(Vertex, position)},
        {1, 3, GL_FLOAT, offsetof(Vertex, normal)},
        {2, 2, GL_FLOAT, offsetof(Vertex, uv)},
    };
    for (const auto& a : attribs) {
        glEnableVertexArrayAttrib(vao_.id(), a.loc);
        glVertexArrayAttribFormat(vao_.id(), a.loc, a.size, a.type, GL_FALSE, GLuint(a.offset));
        glVertexArrayAttribBinding(vao_.id(), a.loc, 0);
    }
    glEnableVertexArrayAttrib(vao_.id(), 3);
    glVertexArrayAttribIFormat(vao_.id(), 3, 1, GL_UNSIGNED_INT, GLuint(offsetof(Vertex, material)));
    glVertexArrayAttribBinding(vao_.id(), 3, 0);
    if (hasNormalMaps_) {
        tangents_ = Buffer::fromVector("scene.tangents", tangents);
        glVertexArrayVertexBuffer(vao_.id(), 1, tangents_.id(), 0, sizeof(glm::vec4));
        glEnableVertexArrayAttrib(vao_.id(), 4);
        glVertexArrayAttribFormat(vao_.id(), 4, 4, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao_.id(), 4, 1);
    }

    // Textures: only what the scene uses; a scene without textures gets a 1x1 white layer to bind.
    uploadNormalTextures(scene);
    std::vector<int> layerOf(scene.textures.size(), -1);
    int layers = 0;
    for (const core::Material& m : scene.materials)
        if (m.baseColorTexture >= 0 && layerOf[m.baseColorTexture] < 0) layerOf[m.baseColorTexture] = layers++;
    hasTextures_ = layers > 0;
    const int size = hasTextures_ ? textureSize : 1;
    textures_ = Texture::create2DArray("scene.baseColorTextures", GL_SRGB8_ALPHA8, size, size, std::max(layers, 1));
    std::vector<std::uint8_t> texels(std::size_t(size) * size * 4, 255);
    for (std::size_t t = 0; t < scene.textures.size(); ++t) {
        if (layerOf[t] < 0) continue;
        resampleInto(scene.textures[t], size, texels.data());
        glTextureSubImage3D(textures_.id(), 0, 0, 0, layerOf[t], size, size, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                            texels.data());
    }
    if (!hasTextures_)
        glTextureSubImage3D(textures_.id(), 0, 0, 0, 0, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
    textures_.setFilter(GL_LINEAR, GL_LINEAR);
    textures_.setWrap(GL_REPEAT);

    emissive_ =
        Buffer("scene.emissiveTriangles",
               sizeof(GpuEmissiveHeader) + std::max<std::size_t>(emitters_.size(), 1) * sizeof(GpuEmissiveTriangle));
    placeEmitters(vertices);

    std::vector<GpuMaterial> mats;
    for (const core::Material& m : scene.materials) {
        // base_color.glsl's alphaCutOut: baseAlpha x texture alpha < cutoff, with cutoff 0 (never) when opaque.
        const float cutoff = m.isMasked() ? m.alphaCutoff : 0.0f;
        mats.push_back({glm::vec4(m.baseColor, m.metallic), glm::vec4(m.emission, m.roughness),
                        glm::vec4(m.specularColor, m.specular),
                        glm::ivec4(m.baseColorTexture >= 0 ? layerOf[m.baseColorTexture] : -1, m.doubleSided,
                                   std::bit_cast<int>(cutoff), std::bit_cast<int>(m.baseAlpha)),
                        glm::ivec4(m.hasNormalMap() ? normalLayerOf_[m.normalTexture] : -1,
                                   std::bit_cast<int>(m.normalScale), 0, 0)});
    }
    if (mats.empty()) mats.push_back({});
    materials_ = Buffer::fromVector("scene.materials", mats);

    setLights(scene.lights);
}

void GpuScene::uploadNormalTextures(const core::Scene& scene)
{
    // The layers of the textures that serve as normal maps (a texture that is both a base colour and a
    // normal map is uploaded twice: sRGB-decoded in the one array, linear in this one).
    normalLayerOf_.assign(scene.textures.size(), -1);
    int layers = 0;
    if (hasNormalMaps_)
        for (const core::Material& m : scene.materials)
            if (m.hasNormalMap() && normalLayerOf_[m.normalTexture] < 0) normalLayerOf_[m.normalTexture] = layers++;
    // At the largest map's own side (up to kMaxNormalMapSize), not the base colours' textureSize: light is not
    // linear in the normal, so a box-filtered map (the mean of the encoded normals, made unit again in the
    // shader) lights a surface as a smoother one, and the path tracer reads the maps as the file has them.
    // Crytek Sponza's 1024^2 maps at 512^2 took sponza-spot's still direct light from 4.7% to 8.3% of the
    // path tracer's (256x256, 64 frames, 4x4-pixel blocks). Smaller maps are enlarged to that side, nearest.
    // A flat normal (0.5, 0.5, 1) fills the one texel of a scene without maps.
    int size = 1;
    for (std::size_t t = 0; t < scene.textures.size(); ++t)
        if (normalLayerOf_[t] >= 0)
            size = std::max({size, std::min(scene.textures[t].width, kMaxNormalMapSize),
                             std::min(scene.textures[t].height, kMaxNormalMapSize)});
    normalTextures_ = Texture::create2DArray("scene.normalTextures", GL_RGBA8, size, size, std::max(layers, 1));
    std::vector<std::uint8_t> texels(std::size_t(size) * size * 4, 255);
    for (std::size_t t = 0; t < scene.textures.size(); ++t) {
        if (normalLayerOf_[t] < 0) continue;
        resampleInto(scene.textures[t], size, texels.data());
        glTextureSubImage3D(normalTextures_.id(), 0, 0, 0, normalLayerOf_[t], size, size, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                            texels.data());
    }
    if (layers == 0) {
        const std::uint8_t flat[4] = {128, 128, 255, 255};
        glTextureSubImage3D(normalTextures_.id(), 0, 0, 0, 0, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, flat);
    }
    normalTextures_.setFilter(GL_LINEAR, GL_LINEAR);
    normalTextures_.setWrap(GL_REPEAT);
}

void GpuScene::placeEmitters(const std::vector<Vertex>& vertices)
{
    // The area lights, and the emissive triangles with a power CDF (luminance of pi L A), for sampling
    // emission by power.
    area_.clear();
    std::vector<GpuEmissiveTriangle> emissive;
    double totalPower = 0.0;
    for (const Emitter& e : emitters_) {
        const glm::vec3 a = vertices[e.corners[0]].position, b = vertices[e.corners[1]].position,
                        c = vertices[e.corners[2]].position;
        const glm::vec3 cross = glm::cross(b - a, c - a);
        const float area = 0.5f * glm::length(cross);
        if (!(area > 0.0f)) continue; // degenerate (flattened by moveVertices): emits nothing
        totalPower += core::kPi * e.luminance * area;
        emissive.push_back({e.triangle, e.material, area, float(totalPower)});
        if (!e.light) continue;
        LightSource s;
        s.type = kLightArea;
        s.triangle[0] = a;
        s.triangle[1] = b;
        s.triangle[2] = c;
        s.direction = glm::normalize(cross);
        s.intensity = e.emission;
        s.group = e.group;
        area_.push_back(s);
    }
    // Area lights of one mesh: their shadow cube sits at the mesh's emitting centroid, nudged off the
    // surface along the normal so the emitter does not shadow itself.
    for (LightSource& s : area_) {
        glm::vec3 sum(0.0f);
        int n = 0;
        for (const LightSource& o : area_)
            if (o.group == s.group) {
                sum += (o.triangle[0] + o.triangle[1] + o.triangle[2]) / 3.0f;
                ++n;
            }
        s.position = sum / float(n) + s.direction * 1e-3f;
    }
    for (GpuEmissiveTriangle& e : emissive) e.powerCdf = totalPower > 0.0 ? float(e.powerCdf / totalPower) : 1.0f;
    if (!emissive.empty()) emissive.back().powerCdf = 1.0f;
    emissiveCount_ = int(emissive.size());
    const GpuEmissiveHeader header{std::uint32_t(emissive.size()), float(totalPower), {0, 0}};
    emissive_.update(0, sizeof header, &header);
    if (!emissive.empty())
        emissive_.update(sizeof header, emissive.size() * sizeof(GpuEmissiveTriangle), emissive.data());
}

void GpuScene::setLights(const std::vector<core::Light>& punctual)
{
    punctual_ = punctual;
    lights_.clear();
    for (const core::Light& l : punctual) {
        LightSource s;
        s.type = l.type == core::LightType::Point  ? kLightPoint
                 : l.type == core::LightType::Spot ? kLightSpot
                                                   : kLightDirectional;
        s.position = l.position;
        s.direction = glm::normalize(l.direction);
        s.intensity = l.intensity;
        s.outerConeRad = l.outerConeRad;
        s.cosOuter = std::cos(l.outerConeRad);
        s.cosInner = std::cos(std::min(l.innerConeRad, l.outerConeRad));
        lights_.push_back(s);
    }
    lights_.insert(lights_.end(), area_.begin(), area_.end());
}

std::vector<Define> GpuScene::alphaMaskDefines() const
{
    if (!hasAlphaMask_) return {};
    return {{"ALPHA_MASK", "1"}};
}

bool GpuScene::moveVertices(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals)
{
    const std::size_t n = vertexCount();
    if (positions.size() != n || normals.size() != n) return false;
    const auto finite = [](const glm::vec3& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    for (std::size_t i = 0; i < n; ++i)
        if (!finite(positions[i]) || !finite(normals[i])) return false;
    std::vector<Vertex> vertices = vertices_.download<Vertex>();
    core::Bounds bounds;
    for (std::size_t i = 0; i < n; ++i) {
        vertices[i].position = positions[i];
        vertices[i].normal = normals[i];
        bounds.extend(positions[i]);
    }
    vertices_.update(0, n * sizeof(Vertex), vertices.data());
    bounds_ = bounds;
    placeEmitters(vertices); // the area lights and the emissive triangles where the vertices now are
    setLights(punctual_);
    return true;
}

void GpuScene::bindGeometry() const
{
    vertices_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCENE_VERTICES);
    indices_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCENE_INDICES);
    emissive_.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_SCENE_EMISSIVE);
    textures_.bind(UNIT_BASE_COLOR);
}

void GpuScene::draw() const
{
    vao_.bind();
    glDrawElements(GL_TRIANGLES, GLsizei(indexCount_), GL_UNSIGNED_INT, nullptr);
}

void GpuScene::IndexRanges::add(std::size_t first, std::size_t count)
{
    if (count == 0) return;
    if (!counts.empty() && first == end) { // follows the last range: extend it
        counts.back() += int(count);
    } else {
        counts.push_back(int(count));
        offsets.push_back(reinterpret_cast<const void*>(first * sizeof(std::uint32_t)));
    }
    end = first + count;
}

void GpuScene::draw(Meshes which) const
{
    const IndexRanges& r = which == Meshes::Masked ? maskedRanges_ : opaqueRanges_;
    if (r.counts.empty()) return;
    vao_.bind();
    glMultiDrawElements(GL_TRIANGLES, r.counts.data(), GL_UNSIGNED_INT, r.offsets.data(), GLsizei(r.counts.size()));
}

void GpuScene::drawWithAdjacency() const
{
    if (!adjacency_) {
        const std::vector<Vertex> vertices = vertices_.download<Vertex>();
        std::vector<glm::vec3> positions(vertices.size());
        for (std::size_t i = 0; i < vertices.size(); ++i) positions[i] = vertices[i].position;
        adjacency_ = Buffer::fromVector("scene.adjacency",
                                        core::triangleAdjacency(positions, indices_.download<std::uint32_t>()));
        adjacencyVao_ = VertexArray("scene.adjacency");
        glVertexArrayVertexBuffer(adjacencyVao_.id(), 0, vertices_.id(), 0, sizeof(Vertex));
        glEnableVertexArrayAttrib(adjacencyVao_.id(), 0);
        glVertexArrayAttribFormat(adjacencyVao_.id(), 0, 3, GL_FLOAT, GL_FALSE, GLuint(offsetof(Vertex, position)));
        glVertexArrayAttribBinding(adjacencyVao_.id(), 0, 0);
        glVertexArrayElementBuffer(adjacencyVao_.id(), adjacency_.id());
    }
    adjacencyVao_.bind();
    glDrawElements(GL_TRIANGLES_ADJACENCY, GLsizei(indexCount_ * 2), GL_UNSIGNED_INT, nullptr);
}

} // namespace bounce::gl
