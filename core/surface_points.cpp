#include "core/surface_points.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <string>
#include <utility>

#include "core/sampling.h"
#include "core/texture_sampling.h"

namespace bounce::core {

namespace {

// The first global triangle index of every mesh, plus the total at the end.
std::vector<std::size_t> triangleOffsets(const Scene& scene)
{
    std::vector<std::size_t> offsets{0};
    for (const Mesh& m : scene.meshes) offsets.push_back(offsets.back() + m.indices.size() / 3);
    return offsets;
}

struct TriangleRef {
    const Mesh* mesh;
    std::size_t first; // index of the triangle's first entry in mesh->indices
};

TriangleRef findTriangle(const Scene& scene, const std::vector<std::size_t>& offsets, std::uint32_t triangle)
{
    if (triangle >= offsets.back())
        throw SurfacePointError("surface point on triangle " + std::to_string(triangle) + ", but the scene has " +
                                std::to_string(offsets.back()) + " triangles");
    const auto mesh =
        std::size_t(std::upper_bound(offsets.begin(), offsets.end(), std::size_t(triangle)) - offsets.begin()) - 1;
    return {&scene.meshes[mesh], (triangle - offsets[mesh]) * 3};
}

// Draws per candidate after which the masks are taken to leave no surface (an opaque share under 1/64).
constexpr std::size_t kMaxDrawsPerCandidate = 64;

template <class V>
V interpolate(const V& a, const V& b, const V& c, glm::vec2 bary)
{
    return bary.x * a + bary.y * b + (1.0f - bary.x - bary.y) * c;
}

// A uniform 3D grid over a subset of points, stored sparsely (surfaces fill few cells of their bounding
// box): the points sorted by cell, and an open-addressing table from a cell's key to its run.
class CellGrid {
public:
    CellGrid(const std::vector<glm::vec3>& points, const std::vector<std::uint32_t>& subset, float cell,
             const Bounds& bounds)
        : lo_(bounds.lo)
    {
        // 21 bits per axis in the key: the cell is never smaller than the extent / 2^20.
        const glm::vec3 extent = bounds.extent();
        const float largest = std::max({extent.x, extent.y, extent.z});
        cell_ = std::max({cell, largest * 0x1p-20f, std::numeric_limits<float>::min()});
        std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
        keyed.reserve(subset.size());
        for (std::uint32_t i : subset) keyed.emplace_back(key(cellOf(points[i])), i);
        std::sort(keyed.begin(), keyed.end());
        order_.resize(keyed.size());
        for (std::size_t i = 0; i < keyed.size(); ++i) order_[i] = keyed[i].second;

        std::size_t cells = 0;
        for (std::size_t i = 0; i < keyed.size(); ++i) cells += i == 0 || keyed[i].first != keyed[i - 1].first;
        std::size_t capacity = 16;
        while (capacity < 2 * cells) capacity *= 2;
        slots_.assign(capacity, Slot{});
        for (std::size_t i = 0; i < keyed.size();) {
            std::size_t j = i;
            while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
            Slot& s = slotFor(keyed[i].first);
            s = {keyed[i].first, std::uint32_t(i), std::uint32_t(j), true};
            i = j;
        }
    }

    // Calls f(index) for every point of the subset in the 27 cells around p (all points within one
    // cell size of p, and some more).
    template <class F>
    void forNeighbours(const glm::vec3& p, F&& f) const
    {
        const glm::ivec3 c = cellOf(p);
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const glm::ivec3 n = c + glm::ivec3(dx, dy, dz);
                    if (glm::any(glm::lessThan(n, glm::ivec3(0))) ||
                        glm::any(glm::greaterThan(n, glm::ivec3(kMaxCell))))
                        continue;
                    const Slot& s = slotFor(key(n));
                    if (!s.used) continue;
                    for (std::uint32_t k = s.begin; k < s.end; ++k) f(order_[k]);
                }
    }

private:
    static constexpr int kMaxCell = (1 << 21) - 1;
    struct Slot {
        std::uint64_t key = 0;
        std::uint32_t begin = 0, end = 0;
        bool used = false;
    };

    glm::ivec3 cellOf(const glm::vec3& p) const
    {
        const glm::vec3 c = glm::floor((p - lo_) / cell_);
        return glm::clamp(glm::ivec3(c), glm::ivec3(0), glm::ivec3(kMaxCell));
    }
    static std::uint64_t key(const glm::ivec3& c)
    {
        return std::uint64_t(c.x) | (std::uint64_t(c.y) << 21) | (std::uint64_t(c.z) << 42);
    }
    // The slot holding `k`, or the empty slot where it would go (linear probing).
    Slot& slotFor(std::uint64_t k) { return const_cast<Slot&>(std::as_const(*this).slotFor(k)); }
    const Slot& slotFor(std::uint64_t k) const
    {
        const std::size_t mask = slots_.size() - 1;
        for (std::size_t i = std::size_t(mixBits(k)) & mask;; i = (i + 1) & mask)
            if (!slots_[i].used || slots_[i].key == k) return slots_[i];
    }

    glm::vec3 lo_;
    float cell_ = 1.0f;
    std::vector<std::uint32_t> order_;
    std::vector<Slot> slots_;
};

float distanceSquared(const glm::vec3& a, const glm::vec3& b)
{
    const glm::vec3 d = a - b;
    return glm::dot(d, d);
}

// Step 2: sequential dart throwing over the candidates in index order; a candidate lands when no
// earlier dart lies closer than r.
std::vector<std::uint32_t> throwDarts(const std::vector<glm::vec3>& candidates, float r, const Bounds& bounds)
{
    std::vector<std::uint32_t> all(candidates.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = std::uint32_t(i);
    const CellGrid grid(candidates, all, r, bounds);
    std::vector<char> landed(candidates.size(), 0);
    std::vector<std::uint32_t> darts;
    const float r2 = r * r;
    for (std::uint32_t i = 0; i < candidates.size(); ++i) {
        bool free = true;
        grid.forNeighbours(candidates[i], [&](std::uint32_t j) {
            if (free && landed[j] && distanceSquared(candidates[i], candidates[j]) < r2) free = false;
        });
        if (!free) continue;
        landed[i] = 1;
        darts.push_back(i);
    }
    return darts;
}

// Step 3: Yuksel 2015's weighted elimination down to `count` points. w_ij = (1 - d_ij / (2 r_max))^8
// for d_ij < 2 r_max (Eq. 1, alpha = 8); the point with the largest total weight goes first, and its
// neighbours' weights drop by what it gave them.
std::vector<std::uint32_t> eliminate(const std::vector<glm::vec3>& candidates, std::vector<std::uint32_t> darts,
                                     std::size_t count, double rMax, const Bounds& bounds)
{
    if (darts.size() <= count) return darts;
    const float reach = float(2.0 * rMax);
    const CellGrid grid(candidates, darts, reach, bounds);
    // Neighbour lists (compressed rows over the darts' positions in `darts`).
    std::vector<std::uint32_t> slotOf(candidates.size(), 0);
    for (std::size_t k = 0; k < darts.size(); ++k) slotOf[darts[k]] = std::uint32_t(k);
    std::vector<std::size_t> rowStart{0};
    std::vector<std::uint32_t> neighbour;
    std::vector<float> weight;
    std::vector<double> total(darts.size(), 0.0);
    for (std::size_t k = 0; k < darts.size(); ++k) {
        const glm::vec3 p = candidates[darts[k]];
        grid.forNeighbours(p, [&](std::uint32_t j) {
            if (j == darts[k]) return;
            const float d = std::sqrt(distanceSquared(p, candidates[j]));
            if (d >= reach) return;
            const float w = float(std::pow(1.0 - double(d) / reach, 8.0));
            neighbour.push_back(slotOf[j]);
            weight.push_back(w);
            total[k] += w;
        });
        rowStart.push_back(neighbour.size());
    }
    // A max-heap with lazy deletion: an entry is stale when its weight is no longer the point's.
    using Entry = std::pair<double, std::uint32_t>;
    std::priority_queue<Entry> heap;
    for (std::size_t k = 0; k < darts.size(); ++k) heap.emplace(total[k], std::uint32_t(k));
    std::vector<char> removed(darts.size(), 0);
    for (std::size_t left = darts.size(); left > count;) {
        const auto [w, k] = heap.top();
        heap.pop();
        if (removed[k] || w != total[k]) continue;
        removed[k] = 1;
        --left;
        for (std::size_t e = rowStart[k]; e < rowStart[k + 1]; ++e) {
            const std::uint32_t j = neighbour[e];
            if (removed[j]) continue;
            total[j] -= weight[e];
            heap.emplace(total[j], j);
        }
    }
    std::vector<std::uint32_t> kept;
    kept.reserve(count);
    for (std::size_t k = 0; k < darts.size(); ++k)
        if (!removed[k]) kept.push_back(darts[k]);
    return kept;
}

} // namespace

std::vector<double> triangleAreas(const Scene& scene)
{
    std::vector<double> areas;
    areas.reserve(scene.triangleCount());
    for (const Mesh& m : scene.meshes)
        for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
            const glm::dvec3 a(m.positions[m.indices[i]]), b(m.positions[m.indices[i + 1]]),
                c(m.positions[m.indices[i + 2]]);
            areas.push_back(0.5 * glm::length(glm::cross(b - a, c - a)));
        }
    return areas;
}

SurfacePoints sampleSurfacePoints(const Scene& scene, std::size_t count, std::uint64_t seed)
{
    if (const std::string problem = scene.validate(); !problem.empty())
        throw SurfacePointError("cannot place surface points on an invalid scene: " + problem);
    SurfacePoints out;
    const std::vector<double> areas = triangleAreas(scene);
    const DiscreteDistribution pick(areas);
    out.totalAreaM2 = pick.total();
    if (count == 0) return out;
    if (pick.empty()) throw SurfacePointError("cannot place surface points: the scene has no surface area");
    if (count > (std::size_t(1) << 31) / kCandidatesPerPoint)
        throw SurfacePointError("too many surface points: " + std::to_string(count));

    // Step 1: candidates uniform by area, in random order (their index order). A candidate in a hole of an
    // alpha mask is drawn again, and the surface area becomes the opaque part's: the total times the share
    // of draws that landed outside the holes.
    const std::vector<std::size_t> offsets = triangleOffsets(scene);
    const std::size_t candidateCount = count * kCandidatesPerPoint;
    std::vector<SurfacePoint> candidates(candidateCount);
    std::vector<glm::vec3> positions(candidateCount);
    Pcg32 rng(mixBits(seed), mixBits(seed ^ 0x5eed5eed5eedull));
    const AlphaMasks masks(scene);
    std::size_t draws = 0;
    for (std::size_t i = 0; i < candidateCount; ++draws) {
        if (draws == kMaxDrawsPerCandidate * candidateCount)
            throw SurfacePointError("cannot place surface points: the alpha masks cut out nearly all of the surface");
        float remapped = 0.0f;
        const auto triangle = std::uint32_t(pick.sample(rng.nextFloat(), &remapped));
        const glm::vec2 bary = sampleUniformTriangle({remapped, rng.nextFloat()});
        const TriangleRef t = findTriangle(scene, offsets, triangle);
        const auto& idx = t.mesh->indices;
        const Material& material = scene.materials[t.mesh->material];
        if (masks.any() && material.isMasked() && t.mesh->uvs.size() == t.mesh->positions.size() &&
            masks.cutOut(material, interpolate(t.mesh->uvs[idx[t.first]], t.mesh->uvs[idx[t.first + 1]],
                                               t.mesh->uvs[idx[t.first + 2]], bary)))
            continue;
        candidates[i] = {triangle, bary, 0.0f};
        positions[i] = interpolate(t.mesh->positions[idx[t.first]], t.mesh->positions[idx[t.first + 1]],
                                   t.mesh->positions[idx[t.first + 2]], bary);
        ++i;
    }
    out.totalAreaM2 *= double(candidateCount) / double(draws);

    // Step 2, restarting with a smaller radius while fewer than `count` darts land. After 60 restarts
    // (r below 1e-6 of the first) every candidate lands: 5N candidates are always enough.
    Bounds bounds;
    for (const glm::vec3& p : positions) bounds.extend(p);
    double r = kMinDistanceFactor * std::sqrt(out.totalAreaM2 / double(count));
    std::vector<std::uint32_t> darts;
    for (;; r *= 0.8, ++out.restarts) {
        if (out.restarts == 60) r = 0.0;
        darts = throwDarts(positions, float(r), bounds);
        if (darts.size() >= count) break;
    }
    out.minDistance = r;

    // Step 3. r_max is the hexagonal-packing radius of Yuksel 2015, Eq. 5 (2D domain of area A).
    const double rMax = std::sqrt(out.totalAreaM2 / (2.0 * std::sqrt(3.0) * double(count)));
    const std::vector<std::uint32_t> kept = eliminate(positions, std::move(darts), count, rMax, bounds);
    const auto share = float(out.totalAreaM2 / double(count));
    out.points.reserve(kept.size());
    for (std::uint32_t i : kept) {
        SurfacePoint p = candidates[i];
        p.areaM2 = share;
        out.points.push_back(p);
    }
    return out;
}

SurfaceSample evaluateSurfacePoint(const Scene& scene, const SurfacePoint& point)
{
    return evaluateSurfacePoints(scene, {point}).front();
}

std::vector<SurfaceSample> evaluateSurfacePoints(const Scene& scene, const std::vector<SurfacePoint>& points)
{
    const std::vector<std::size_t> offsets = triangleOffsets(scene);
    std::vector<SurfaceSample> out;
    out.reserve(points.size());
    for (const SurfacePoint& sp : points) {
        const TriangleRef t = findTriangle(scene, offsets, sp.triangle);
        const Mesh& m = *t.mesh;
        const std::uint32_t i0 = m.indices[t.first], i1 = m.indices[t.first + 1], i2 = m.indices[t.first + 2];
        SurfaceSample s;
        s.position = interpolate(m.positions[i0], m.positions[i1], m.positions[i2], sp.barycentrics);
        const glm::vec3 face = glm::cross(m.positions[i1] - m.positions[i0], m.positions[i2] - m.positions[i0]);
        const float faceLength = glm::length(face);
        s.geometricNormal = faceLength > 0.0f ? face / faceLength : glm::vec3(0.0f);
        const glm::vec3 n = m.normals.size() == m.positions.size()
                                ? interpolate(m.normals[i0], m.normals[i1], m.normals[i2], sp.barycentrics)
                                : s.geometricNormal;
        const float nLength = glm::length(n);
        // Opposite vertex normals can cancel; the face normal is then the only sensible answer.
        s.normal = nLength > 1e-6f ? n / nLength : s.geometricNormal;
        out.push_back(s);
    }
    return out;
}

} // namespace bounce::core
