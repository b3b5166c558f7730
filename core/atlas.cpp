#include "core/atlas.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <unordered_map>

#include "core/sampling.h"

namespace bounce::core {

namespace {

struct Triangles {
    std::vector<std::array<glm::vec3, 3>> corners;
    std::vector<std::array<std::uint32_t, 3>> welded; // vertex ids after welding by position
};

// Every triangle of the scene in global order, with corners welded by position (quantised to a
// millionth of the scene's extent), so that meshes that split vertices for their normals still share
// edges.
Triangles gatherTriangles(const Scene& scene)
{
    Triangles t;
    const Bounds b = scene.bounds();
    const glm::vec3 e = b.extent();
    const float quantum = std::max({e.x, e.y, e.z, 1e-12f}) * 1e-6f;
    std::unordered_map<std::uint64_t, std::uint32_t> ids;
    const auto weld = [&](const glm::vec3& p) {
        const glm::vec3 q = glm::round((p - b.lo) / quantum);
        const std::uint64_t key = (std::uint64_t(std::uint32_t(q.x)) & 0x1FFFFF) |
                                  ((std::uint64_t(std::uint32_t(q.y)) & 0x1FFFFF) << 21) |
                                  ((std::uint64_t(std::uint32_t(q.z)) & 0x1FFFFF) << 42);
        return ids.emplace(key, std::uint32_t(ids.size())).first->second;
    };
    for (const Mesh& m : scene.meshes)
        for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
            std::array<glm::vec3, 3> c{};
            std::array<std::uint32_t, 3> w{};
            for (int k = 0; k < 3; ++k) {
                c[k] = m.positions[m.indices[i + k]];
                w[k] = weld(c[k]);
            }
            t.corners.push_back(c);
            t.welded.push_back(w);
        }
    return t;
}

glm::vec3 faceNormal(const std::array<glm::vec3, 3>& c, float& area)
{
    const glm::vec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
    const float len = glm::length(n);
    area = 0.5f * len;
    return len > 0.0f ? n / len : glm::vec3(0.0f);
}

// Chart of every triangle by region growing over shared edges (step 1 of atlas.h).
std::vector<std::uint32_t> growCharts(const Triangles& t, float cosMax, std::vector<glm::vec3>& chartNormals,
                                      std::vector<std::uint32_t>& seeds)
{
    const std::size_t n = t.corners.size();
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> edges;
    const auto edgeKey = [](std::uint32_t a, std::uint32_t b) {
        return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
    };
    for (std::uint32_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) edges[edgeKey(t.welded[i][k], t.welded[i][(k + 1) % 3])].push_back(i);
    std::vector<glm::vec3> normals(n);
    std::vector<float> areas(n);
    for (std::size_t i = 0; i < n; ++i) normals[i] = faceNormal(t.corners[i], areas[i]);

    constexpr std::uint32_t kNone = ~0u;
    std::vector<std::uint32_t> chart(n, kNone);
    std::vector<std::uint32_t> stack;
    for (std::uint32_t seed = 0; seed < n; ++seed) {
        if (chart[seed] != kNone) continue;
        const auto id = std::uint32_t(chartNormals.size());
        glm::vec3 normal = normals[seed];
        if (normal == glm::vec3(0.0f)) normal = {0.0f, 0.0f, 1.0f}; // a degenerate seed: any plane
        chartNormals.push_back(normal);
        seeds.push_back(seed);
        chart[seed] = id;
        stack.assign(1, seed);
        while (!stack.empty()) {
            const std::uint32_t cur = stack.back();
            stack.pop_back();
            for (int k = 0; k < 3; ++k) {
                const std::vector<std::uint32_t>& across = edges[edgeKey(t.welded[cur][k], t.welded[cur][(k + 1) % 3])];
                // Only across manifold edges: where more surfaces meet (a wall between two rooms' floors)
                // the sides belong to different charts, which the transfer tells apart.
                if (across.size() != 2) continue;
                for (std::uint32_t nb : across) {
                    if (chart[nb] != kNone) continue;
                    const bool degenerate = normals[nb] == glm::vec3(0.0f);
                    if (!degenerate && glm::dot(normals[nb], normal) < cosMax) continue;
                    chart[nb] = id;
                    stack.push_back(nb);
                }
            }
        }
    }
    return chart;
}

struct Placed {
    glm::vec2 lo{1e30f}, hi{-1e30f}; // projected extent, metres
    glm::ivec2 interior{1};
};

} // namespace

glm::ivec4 Atlas::interior(std::uint32_t chart) const
{
    const AtlasChart& c = charts.at(chart);
    return {c.origin.x + gutter, c.origin.y + gutter, c.origin.x + c.size.x - gutter, c.origin.y + c.size.y - gutter};
}

double surfaceArea(const Scene& scene)
{
    double area = 0.0;
    for (const Mesh& m : scene.meshes)
        for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
            const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                            c = m.positions[m.indices[i + 2]];
            area += 0.5 * double(glm::length(glm::cross(b - a, c - a)));
        }
    return area;
}

float texelsPerMetreFor(const Scene& scene, double texels)
{
    const double area = surfaceArea(scene);
    if (!(area > 0.0) || !(texels > 0.0)) throw AtlasError("atlas: the scene has no surface area");
    return float(std::sqrt(texels / area));
}

Atlas buildAtlas(const Scene& scene, const AtlasSettings& settings)
{
    if (!(settings.texelsPerMetre > 0.0f) || !std::isfinite(settings.texelsPerMetre))
        throw AtlasError("atlas: the texel density must be positive and finite, not " +
                         std::to_string(settings.texelsPerMetre));
    if (settings.gutter < 2) throw AtlasError("atlas: the gutter must be at least 2 texels");
    const Triangles tris = gatherTriangles(scene);
    if (tris.corners.empty()) throw AtlasError("atlas: the scene has no triangle");

    Atlas atlas;
    atlas.texelsPerMetre = settings.texelsPerMetre;
    atlas.gutter = settings.gutter;
    atlas.surfaceAreaM2 = surfaceArea(scene);
    std::vector<glm::vec3> normals;
    std::vector<std::uint32_t> seeds;
    atlas.triangleChart = growCharts(tris, std::cos(settings.maxNormalAngleRad), normals, seeds);

    // Step 2: project every chart on its plane.
    const std::size_t chartCount = normals.size();
    atlas.charts.resize(chartCount);
    std::vector<Placed> placed(chartCount);
    for (std::size_t c = 0; c < chartCount; ++c) {
        const Frame f = Frame::fromNormal(normals[c]);
        atlas.charts[c].normal = normals[c];
        atlas.charts[c].axisU = f.t;
        atlas.charts[c].axisV = f.b;
        atlas.charts[c].firstTriangle = seeds[c];
    }
    const auto project = [&](std::uint32_t c, const glm::vec3& p) {
        return glm::vec2(glm::dot(p, atlas.charts[c].axisU), glm::dot(p, atlas.charts[c].axisV));
    };
    for (std::size_t i = 0; i < tris.corners.size(); ++i) {
        const std::uint32_t c = atlas.triangleChart[i];
        ++atlas.charts[c].triangleCount;
        for (const glm::vec3& p : tris.corners[i]) {
            const glm::vec2 q = project(c, p);
            placed[c].lo = glm::min(placed[c].lo, q);
            placed[c].hi = glm::max(placed[c].hi, q);
        }
    }
    const float d = settings.texelsPerMetre;
    for (std::size_t c = 0; c < chartCount; ++c) {
        // Local texel coordinates (q - lo) d + 0.5 span [0.5, extent d + 0.5]: the touched texels are
        // 0 .. floor(extent d + 0.5).
        const glm::vec2 ext = (placed[c].hi - placed[c].lo) * d;
        placed[c].interior = glm::ivec2(glm::floor(ext + 0.5f)) + 1;
        if (glm::any(glm::greaterThan(placed[c].interior, glm::ivec2(settings.maxSize))))
            throw AtlasError("atlas: a chart of " + std::to_string(placed[c].interior.x) + "x" +
                             std::to_string(placed[c].interior.y) + " texels exceeds the maximum atlas size " +
                             std::to_string(settings.maxSize) + ": lower the texel density");
        atlas.charts[c].size = placed[c].interior + 2 * settings.gutter;
    }

    // Step 3: shelf packing, tallest first, into a width about the square root of the charts' area.
    std::vector<std::uint32_t> order(chartCount);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return atlas.charts[a].size.y > atlas.charts[b].size.y; });
    double rectArea = 0.0;
    int widest = 0;
    for (const AtlasChart& c : atlas.charts) {
        rectArea += double(c.size.x) * double(c.size.y);
        widest = std::max(widest, c.size.x);
    }
    const int width = std::max(widest, int(std::ceil(std::sqrt(rectArea) * 1.02)));
    int x = 0, y = 0, shelf = 0, used = 0;
    for (std::uint32_t c : order) {
        AtlasChart& ch = atlas.charts[c];
        if (x + ch.size.x > width) {
            y += shelf;
            x = 0;
            shelf = 0;
        }
        ch.origin = {x, y};
        x += ch.size.x;
        used = std::max(used, x);
        shelf = std::max(shelf, ch.size.y);
    }
    atlas.width = used;
    atlas.height = y + shelf;
    if (atlas.width > settings.maxSize || atlas.height > settings.maxSize)
        throw AtlasError("atlas: " + std::to_string(atlas.width) + "x" + std::to_string(atlas.height) +
                         " texels exceed the maximum atlas size " + std::to_string(settings.maxSize) +
                         ": lower the texel density");

    atlas.corners.resize(tris.corners.size());
    for (std::size_t i = 0; i < tris.corners.size(); ++i) {
        const std::uint32_t c = atlas.triangleChart[i];
        const glm::vec2 base = glm::vec2(atlas.charts[c].origin + settings.gutter) + 0.5f;
        for (int k = 0; k < 3; ++k) atlas.corners[i][k] = base + (project(c, tris.corners[i][k]) - placed[c].lo) * d;
    }
    return atlas;
}

float distanceToTriangle(const std::array<glm::vec2, 3>& t, glm::vec2 q)
{
    const float area = (t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[1].y - t[0].y) * (t[2].x - t[0].x);
    bool inside = area != 0.0f;
    float best = 1e30f;
    for (int k = 0; k < 3; ++k) {
        const glm::vec2 a = t[k], b = t[(k + 1) % 3];
        const float side = (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x);
        if (side * area < 0.0f) inside = false;
        const glm::vec2 ab = b - a;
        const float len2 = glm::dot(ab, ab);
        const float s = len2 > 0.0f ? glm::clamp(glm::dot(q - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
        best = std::min(best, glm::length(q - (a + s * ab)));
    }
    return inside ? 0.0f : best;
}

glm::vec4 fillQuad(const std::array<glm::vec2, 3>& t, float margin)
{
    const glm::vec2 lo = glm::min(t[0], glm::min(t[1], t[2])) - margin;
    const glm::vec2 hi = glm::max(t[0], glm::max(t[1], t[2])) + margin;
    return {lo.x, lo.y, hi.x, hi.y};
}

bool fillsTexel(const std::array<glm::vec2, 3>& t, int i, int j, float margin)
{
    return distanceToTriangle(t, glm::vec2(float(i) + 0.5f, float(j) + 0.5f)) <= margin;
}

bool texelTouches(const std::array<glm::vec2, 3>& t, int i, int j)
{
    // Separating axes: x, y and the three edge normals.
    const glm::vec2 sq[4] = {
        {float(i), float(j)}, {float(i + 1), float(j)}, {float(i), float(j + 1)}, {float(i + 1), float(j + 1)}};
    const auto separated = [&](glm::vec2 axis) {
        float a0 = 1e30f, a1 = -1e30f, b0 = 1e30f, b1 = -1e30f;
        for (const glm::vec2& p : t) a0 = std::min(a0, glm::dot(p, axis)), a1 = std::max(a1, glm::dot(p, axis));
        for (const glm::vec2& p : sq) b0 = std::min(b0, glm::dot(p, axis)), b1 = std::max(b1, glm::dot(p, axis));
        return a1 < b0 || b1 < a0;
    };
    if (separated({1.0f, 0.0f}) || separated({0.0f, 1.0f})) return false;
    for (int k = 0; k < 3; ++k) {
        const glm::vec2 e = t[(k + 1) % 3] - t[k];
        if (e != glm::vec2(0.0f) && separated({-e.y, e.x})) return false;
    }
    return true;
}

std::vector<glm::ivec2> touchedTexels(const std::array<glm::vec2, 3>& t)
{
    std::vector<glm::ivec2> out;
    const glm::vec2 lo = glm::min(t[0], glm::min(t[1], t[2])), hi = glm::max(t[0], glm::max(t[1], t[2]));
    for (int j = int(std::floor(lo.y)); j <= int(std::floor(hi.y)); ++j)
        for (int i = int(std::floor(lo.x)); i <= int(std::floor(hi.x)); ++i)
            if (texelTouches(t, i, j)) out.push_back({i, j});
    return out;
}

} // namespace bounce::core
