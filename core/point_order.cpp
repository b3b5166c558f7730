#include "core/point_order.h"

#include <algorithm>
#include <cmath>

namespace bounce::core {

namespace {

glm::vec3 finiteOrZero(const glm::vec3& p)
{
    return (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) ? p : glm::vec3(0.0f);
}

struct Range {
    std::size_t begin, end;
    int level;
    int parentAxis;
};

} // namespace

std::vector<std::uint32_t> medianSplitOrder(const std::vector<glm::vec3>& positions, int levels, SplitAxis rule)
{
    std::vector<std::uint32_t> order(positions.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = std::uint32_t(i);
    // An explicit stack instead of recursion: a 2^20-point list is 20 levels deep either way, but a
    // hostile levels value must not overflow anything.
    std::vector<Range> stack{{0, order.size(), 0, -1}};
    while (!stack.empty()) {
        const Range r = stack.back();
        stack.pop_back();
        if (r.level >= levels || r.end - r.begin < 2) continue;
        int axis = 0;
        if (rule == SplitAxis::Cycle && r.parentAxis >= 0) {
            axis = (r.parentAxis + 1) % 3;
        } else {
            glm::vec3 lo(INFINITY), hi(-INFINITY);
            for (std::size_t i = r.begin; i < r.end; ++i) {
                const glm::vec3 p = finiteOrZero(positions[order[i]]);
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
            const glm::vec3 e = hi - lo;
            axis = (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
        }
        const std::size_t mid = r.begin + (r.end - r.begin) / 2;
        std::nth_element(order.begin() + std::ptrdiff_t(r.begin), order.begin() + std::ptrdiff_t(mid),
                         order.begin() + std::ptrdiff_t(r.end), [&](std::uint32_t a, std::uint32_t b) {
                             const float pa = finiteOrZero(positions[a])[axis];
                             const float pb = finiteOrZero(positions[b])[axis];
                             return pa < pb || (pa == pb && a < b);
                         });
        stack.push_back({r.begin, mid, r.level + 1, axis});
        stack.push_back({mid, r.end, r.level + 1, axis});
    }
    return order;
}

std::vector<SurfacePoint> orderSurfacePoints(const Scene& scene, const std::vector<SurfacePoint>& points, int levels,
                                             SplitAxis rule)
{
    std::vector<glm::vec3> positions;
    positions.reserve(points.size());
    for (const SurfacePoint& p : points) positions.push_back(evaluateSurfacePoint(scene, p).position);
    const std::vector<std::uint32_t> order = medianSplitOrder(positions, levels, rule);
    std::vector<SurfacePoint> out;
    out.reserve(points.size());
    for (std::uint32_t i : order) out.push_back(points[i]);
    return out;
}

int exactLog2(std::uint64_t n)
{
    if (n == 0 || (n & (n - 1)) != 0) return -1;
    int l = 0;
    while ((std::uint64_t(1) << l) < n) ++l;
    return l;
}

} // namespace bounce::core
