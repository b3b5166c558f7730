#include "core/adjacency.h"

#include <cstring>
#include <unordered_map>

namespace bounce::core {

namespace {

struct PositionKey {
    std::uint32_t bits[3];
    bool operator==(const PositionKey& o) const
    {
        return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
    }
};

struct PositionHash {
    std::size_t operator()(const PositionKey& k) const
    {
        std::uint64_t h = 1469598103934665603ull;
        for (std::uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
        return std::size_t(h);
    }
};

} // namespace

std::vector<std::uint32_t> triangleAdjacency(const std::vector<glm::vec3>& positions,
                                             const std::vector<std::uint32_t>& indices)
{
    // Each vertex's position as one id, so that split vertices meet.
    std::unordered_map<PositionKey, std::uint32_t, PositionHash> ids;
    std::vector<std::uint32_t> id(positions.size());
    for (std::size_t v = 0; v < positions.size(); ++v) {
        PositionKey k;
        std::memcpy(k.bits, &positions[v], sizeof k.bits);
        id[v] = ids.emplace(k, std::uint32_t(ids.size())).first->second;
    }
    // Per undirected edge (two position ids): how many triangle edges lie on it, and the first two's
    // triangles and opposite corners.
    struct EdgeUse {
        std::uint32_t count = 0, triangle[2] = {0, 0}, opposite[2] = {0, 0};
    };
    std::unordered_map<std::uint64_t, EdgeUse> edges;
    const auto key = [&](std::uint32_t a, std::uint32_t b) {
        const std::uint64_t x = id[a], y = id[b];
        return x < y ? (x << 32) | y : (y << 32) | x;
    };
    const std::size_t triangles = indices.size() / 3;
    edges.reserve(triangles * 2);
    for (std::size_t t = 0; t < triangles; ++t)
        for (int k = 0; k < 3; ++k) {
            EdgeUse& e = edges[key(indices[3 * t + k], indices[3 * t + (k + 1) % 3])];
            if (e.count < 2) {
                e.triangle[e.count] = std::uint32_t(t);
                e.opposite[e.count] = indices[3 * t + (k + 2) % 3];
            }
            ++e.count;
        }
    std::vector<std::uint32_t> out(triangles * 6);
    for (std::size_t t = 0; t < triangles; ++t)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = indices[3 * t + k], b = indices[3 * t + (k + 1) % 3];
            const std::uint32_t own = indices[3 * t + (k + 2) % 3];
            out[6 * t + 2 * k] = a;
            out[6 * t + 2 * k + 1] = own;
            const EdgeUse& e = edges.at(key(a, b));
            // A triangle that meets itself on an edge (a degenerate one) has no neighbour there.
            if (e.count != 2 || e.triangle[0] == e.triangle[1]) continue;
            out[6 * t + 2 * k + 1] = e.triangle[0] == t ? e.opposite[1] : e.opposite[0];
        }
    return out;
}

} // namespace bounce::core
