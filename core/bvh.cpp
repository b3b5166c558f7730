#include "core/bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace bounce::core {

namespace {

// One triangle as the builder sees it.
struct Ref {
    Bounds bounds;
    glm::vec3 centroid;
};

// The tree before it is flattened.
struct BuildNode {
    Bounds bounds;
    int children[2] = {-1, -1};
    int first = 0, count = 0; // leaf range in the reference order
};

float area(const Bounds& b)
{
    if (b.empty()) return 0.0f;
    const glm::vec3 e = b.hi - b.lo;
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
}

void merge(Bounds& a, const Bounds& b)
{
    a.lo = glm::min(a.lo, b.lo);
    a.hi = glm::max(a.hi, b.hi);
}

// The leaf field packs first << kCountBits | count.
constexpr int kCountBits = 5;
constexpr int kMaxLeafField = (1 << kCountBits) - 1; // the most triangles one leaf can name

class Builder {
public:
    Builder(const std::vector<Ref>& refs, std::vector<std::uint32_t>& order) : refs_(refs), order_(order) {}

    int build(int first, int count, int depth)
    {
        const int index = int(nodes_.size());
        nodes_.emplace_back();
        maxDepth_ = std::max(maxDepth_, depth);
        Bounds bounds, centroids;
        for (int i = first; i < first + count; ++i) {
            merge(bounds, refs_[order_[i]].bounds);
            centroids.extend(refs_[order_[i]].centroid);
        }
        nodes_[index].bounds = bounds;
        nodes_[index].first = first;
        nodes_[index].count = count;
        if (count <= 1) return index;

        int mid = -1;
        // Past the depth limit only a leaf too large for the leaf field is split any further.
        const bool mayLeaf = count <= (depth >= Bvh::kMaxDepth ? kMaxLeafField : Bvh::kMaxLeafSize);
        if (depth < Bvh::kMaxDepth) mid = splitSah(first, count, bounds, centroids, mayLeaf);
        if (mid < 0 && mayLeaf) return index;
        if (mid < 0) mid = splitMedian(first, count, centroids);

        const int left = build(first, mid - first, depth + 1);
        const int right = build(mid, first + count - mid, depth + 1);
        nodes_[index].children[0] = left;
        nodes_[index].children[1] = right;
        nodes_[index].count = 0;
        return index;
    }

    std::vector<BuildNode>& nodes() { return nodes_; }
    int maxDepth() const { return maxDepth_; }

private:
    // Binned SAH with unit costs for a box test and a triangle test: the partition point, or -1 when a
    // leaf is cheaper (and allowed) or no bin boundary separates the centroids.
    int splitSah(int first, int count, const Bounds& bounds, const Bounds& centroids, bool mayLeaf)
    {
        constexpr int kBins = Bvh::kBins;
        float bestCost = std::numeric_limits<float>::infinity();
        int bestAxis = -1, bestBin = -1;
        const glm::vec3 extent = centroids.hi - centroids.lo;
        for (int axis = 0; axis < 3; ++axis) {
            if (!(extent[axis] > 0.0f)) continue;
            std::array<Bounds, kBins> binBounds;
            std::array<int, kBins> binCounts{};
            const float scale = float(kBins) / extent[axis];
            for (int i = first; i < first + count; ++i) {
                const Ref& r = refs_[order_[i]];
                const int b = std::min(kBins - 1, int((r.centroid[axis] - centroids.lo[axis]) * scale));
                merge(binBounds[b], r.bounds);
                ++binCounts[b];
            }
            // Sweep from the right, then from the left: cost of splitting after bin b.
            std::array<float, kBins> rightArea{};
            std::array<int, kBins> rightCount{};
            Bounds acc;
            int n = 0;
            for (int b = kBins - 1; b > 0; --b) {
                merge(acc, binBounds[b]);
                n += binCounts[b];
                rightArea[b] = area(acc);
                rightCount[b] = n;
            }
            acc = Bounds{};
            n = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                merge(acc, binBounds[b]);
                n += binCounts[b];
                if (n == 0 || rightCount[b + 1] == 0) continue;
                const float cost = area(acc) * float(n) + rightArea[b + 1] * float(rightCount[b + 1]);
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = axis;
                    bestBin = b;
                }
            }
        }
        if (bestAxis < 0) return -1;
        const float parentArea = area(bounds);
        const float splitCost = 1.0f + (parentArea > 0.0f ? bestCost / parentArea : 0.0f);
        if (mayLeaf && float(count) <= splitCost) return -1;

        const float scale = float(kBins) / extent[bestAxis];
        const auto it = std::partition(order_.begin() + first, order_.begin() + first + count, [&](std::uint32_t r) {
            const int b = std::min(kBins - 1, int((refs_[r].centroid[bestAxis] - centroids.lo[bestAxis]) * scale));
            return b <= bestBin;
        });
        const int mid = int(it - order_.begin());
        return mid > first && mid < first + count ? mid : -1;
    }

    // Half and half along the widest centroid axis (coincident centroids: any halves).
    int splitMedian(int first, int count, const Bounds& centroids)
    {
        const glm::vec3 e = centroids.extent();
        const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
        const int mid = first + count / 2;
        std::nth_element(
            order_.begin() + first, order_.begin() + mid, order_.begin() + first + count,
            [&](std::uint32_t a, std::uint32_t b) { return refs_[a].centroid[axis] < refs_[b].centroid[axis]; });
        return mid;
    }

    const std::vector<Ref>& refs_;
    std::vector<std::uint32_t>& order_;
    std::vector<BuildNode> nodes_;
    int maxDepth_ = 0;
};

// One depth-first copy of the tree for direction d: at every node the child a ray along d meets first
// (the smaller box centre along the axis for +, the larger for -) comes first.
void flatten(const std::vector<BuildNode>& tree, int node, int direction, std::vector<BvhNode>& out)
{
    const BuildNode& n = tree[node];
    const int index = int(out.size());
    out.push_back({n.bounds.lo, -1, n.bounds.hi, -1});
    if (n.children[0] < 0) {
        out[index].leaf = (n.first << kCountBits) | n.count;
    } else {
        const int axis = direction / 2;
        const bool negative = direction % 2 == 1;
        int a = n.children[0], b = n.children[1];
        const float ca = tree[a].bounds.lo[axis] + tree[a].bounds.hi[axis];
        const float cb = tree[b].bounds.lo[axis] + tree[b].bounds.hi[axis];
        if (negative ? ca < cb : cb < ca) std::swap(a, b);
        flatten(tree, a, direction, out);
        flatten(tree, b, direction, out);
    }
    out[index].miss = int(out.size()); // relative to this copy; fixed up by the caller
}

float gamma(int n)
{
    const float eps = std::numeric_limits<float>::epsilon() * 0.5f;
    return float(n) * eps / (1.0f - float(n) * eps);
}

// Ize 2013: the far slab distance scaled up by 1 + 2 gamma(3) bounds the rounding of the slab distances.
// The nearest hit so far is scaled up too: a triangle's computed t and its box's computed entry distance
// are rounded differently, and a triangle a few ulps nearer than the box says must not be culled.
const float kSlabFarScale = 1.0f + 2.0f * gamma(3);
const float kBestScale = 1.0f + 8.0f * std::numeric_limits<float>::epsilon();

bool hitBox(const WatertightRay& ray, const BvhNode& n, float tMin, float tMax)
{
    const glm::vec3 t0 = (n.lo - ray.origin) * ray.invDir;
    const glm::vec3 t1 = (n.hi - ray.origin) * ray.invDir;
    const glm::vec3 tNear = glm::min(t0, t1), tFar = glm::max(t0, t1);
    const float enter = std::max(std::max(tNear.x, tNear.y), std::max(tNear.z, tMin));
    const float leave = std::min(std::min(tFar.x, tFar.y), tFar.z) * kSlabFarScale;
    return enter <= std::min(leave, tMax * kBestScale);
}

template <bool kAnyHit>
bool walk(const std::vector<BvhNode>& nodes, const std::vector<BvhTriangle>& triangles, std::size_t nodeCount,
          const glm::vec3& origin, const glm::vec3& dir, float tMin, float tMax, RayHit* hit, TraversalStats* stats)
{
    const WatertightRay ray(origin, dir);
    int node = Bvh::directionIndex(dir) * int(nodeCount);
    float best = tMax;
    bool found = false;
    while (node >= 0) {
        const BvhNode& n = nodes[std::size_t(node)];
        if (stats) ++stats->nodes;
        if (!hitBox(ray, n, tMin, best)) {
            node = n.miss;
            continue;
        }
        if (n.leaf < 0) {
            ++node;
            continue;
        }
        const int first = n.leaf >> kCountBits, count = n.leaf & kMaxLeafField;
        for (int i = first; i < first + count; ++i) {
            const BvhTriangle& tri = triangles[std::size_t(i)];
            if (stats) ++stats->triangles;
            float t, b1, b2;
            if (!intersectTriangle(ray, tri.v0, tri.v1, tri.v2, tMin, best, t, b1, b2)) continue;
            if (kAnyHit) return true;
            found = true;
            best = t;
            hit->triangle = tri.index;
            hit->t = t;
            hit->b1 = b1;
            hit->b2 = b2;
        }
        node = n.miss;
    }
    return found;
}

} // namespace

WatertightRay::WatertightRay(const glm::vec3& o, const glm::vec3& dir) : origin(o)
{
    // Woop et al. 2013, Fig. 1: kz the largest |dir| component, kx and ky swapped when dir[kz] < 0 to
    // keep the winding.
    const glm::vec3 a = glm::abs(dir);
    const int kz = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (dir[kz] < 0.0f) std::swap(kx, ky);
    const float sx = dir[kx] / dir[kz], sy = dir[ky] / dir[kz], sz = 1.0f / dir[kz];
    rowX = glm::vec3(0.0f);
    rowY = glm::vec3(0.0f);
    rowZ = glm::vec3(0.0f);
    rowX[kx] = 1.0f;
    rowX[kz] = -sx;
    rowY[ky] = 1.0f;
    rowY[kz] = -sy;
    rowZ[kz] = sz;
    for (int k = 0; k < 3; ++k) {
        // 1/0 would give inf, and 0 * inf = NaN in the slab test for a box face through the origin.
        const float d = std::abs(dir[k]) > 1e-30f ? dir[k] : std::copysign(1e-30f, dir[k]);
        invDir[k] = 1.0f / d;
    }
}

bool intersectTriangle(const WatertightRay& ray, const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2,
                       float tMin, float tMax, float& t, float& b1, float& b2)
{
    // Vertices relative to the origin, sheared so the ray runs along +z (Woop et al. 2013, Sec. 3).
    // Each vertex is transformed by the same operations in every triangle that shares it, so the edge
    // functions of two triangles sharing an edge are exact negatives of each other.
    const glm::vec3 a = v0 - ray.origin, b = v1 - ray.origin, c = v2 - ray.origin;
    const float ax = glm::dot(ray.rowX, a), ay = glm::dot(ray.rowY, a);
    const float bx = glm::dot(ray.rowX, b), by = glm::dot(ray.rowY, b);
    const float cx = glm::dot(ray.rowX, c), cy = glm::dot(ray.rowY, c);
    const float u = cx * by - cy * bx; // weight of v0
    const float v = ax * cy - ay * cx; // weight of v1
    const float w = bx * ay - by * ax; // weight of v2
    // Both sides: inside when all three share a sign; a zero edge function is inside.
    if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) return false;
    const float det = u + v + w;
    if (det == 0.0f) return false;
    const float tScaled = u * glm::dot(ray.rowZ, a) + v * glm::dot(ray.rowZ, b) + w * glm::dot(ray.rowZ, c);
    const float rcp = 1.0f / det;
    t = tScaled * rcp;
    if (!(t > tMin && t < tMax)) return false;
    b1 = v * rcp;
    b2 = w * rcp;
    return true;
}

bool Bvh::hittable(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2)
{
    for (const glm::vec3& p : {p0, p1, p2})
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
    const glm::vec3 n = glm::cross(p1 - p0, p2 - p0);
    return std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z) && n != glm::vec3(0.0f);
}

int Bvh::directionIndex(const glm::vec3& dir)
{
    const glm::vec3 a = glm::abs(dir);
    const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    return 2 * axis + (dir[axis] < 0.0f ? 1 : 0);
}

Bvh::Bvh(const Scene& scene)
{
    std::vector<Ref> refs;
    std::vector<BvhTriangle> all;
    std::uint32_t global = 0;
    for (const Mesh& m : scene.meshes)
        for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3, ++global) {
            const glm::vec3 p0 = m.positions[m.indices[i]], p1 = m.positions[m.indices[i + 1]],
                            p2 = m.positions[m.indices[i + 2]];
            if (!hittable(p0, p1, p2)) {
                ++skipped_;
                continue;
            }
            Ref r;
            r.bounds.extend(p0);
            r.bounds.extend(p1);
            r.bounds.extend(p2);
            r.centroid = r.bounds.centre();
            refs.push_back(r);
            all.push_back({p0, global, p1, 0.0f, p2, 0.0f});
        }

    std::vector<BuildNode> tree;
    std::vector<std::uint32_t> order(refs.size());
    std::iota(order.begin(), order.end(), 0u);
    if (refs.empty()) {
        tree.emplace_back(); // one leaf with no triangles: the walk visits it and ends
    } else {
        Builder builder(refs, order);
        builder.build(0, int(refs.size()), 0);
        tree = std::move(builder.nodes());
        depth_ = builder.maxDepth();
    }
    triangles_.reserve(order.size());
    for (std::uint32_t r : order) triangles_.push_back(all[r]);

    const std::size_t n = tree.size();
    nodes_.reserve(n * kDirections);
    for (int d = 0; d < kDirections; ++d) {
        std::vector<BvhNode> copy;
        copy.reserve(n);
        flatten(tree, 0, d, copy);
        for (BvhNode& node : copy) node.miss = std::size_t(node.miss) >= n ? -1 : node.miss + int(d * n);
        nodes_.insert(nodes_.end(), copy.begin(), copy.end());
    }
}

bool Bvh::closestHit(const glm::vec3& origin, const glm::vec3& dir, float tMin, float tMax, RayHit& hit,
                     TraversalStats* stats) const
{
    return walk<false>(nodes_, triangles_, nodeCount(), origin, dir, tMin, tMax, &hit, stats);
}

bool Bvh::anyHit(const glm::vec3& origin, const glm::vec3& dir, float tMin, float tMax, TraversalStats* stats) const
{
    return walk<true>(nodes_, triangles_, nodeCount(), origin, dir, tMin, tMax, nullptr, stats);
}

} // namespace bounce::core
