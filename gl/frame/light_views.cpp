#include "gl/frame/light_views.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace bounce::gl {

void lightNearFar(const core::Bounds& b, const glm::vec3& origin, float& near, float& far)
{
    float maxDist = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 c(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
        maxDist = std::max(maxDist, glm::length(c - origin));
    }
    far = std::max(maxDist * 1.01f, 1e-3f);
    near = std::max(far * 1e-4f, 1e-5f);
}

glm::vec3 lightUpVector(const glm::vec3& d)
{
    return std::abs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

std::vector<LightView> cubeViews(const glm::vec3& origin, float near, float far)
{
    static const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    std::vector<LightView> v(6);
    for (int f = 0; f < 6; ++f) {
        v[f].view = glm::lookAt(origin, origin + dirs[f], ups[f]);
        v[f].proj = glm::perspective(glm::radians(90.0f), 1.0f, near, far);
        v[f].origin = origin;
        v[f].direction = -glm::vec3(glm::transpose(v[f].view)[2]);
        v[f].cubeFace = true;
        v[f].fovRad = glm::radians(90.0f);
        v[f].far = far;
    }
    return v;
}

namespace {

// The eight corners of the frustum slice [d0, d1] along the view axis: near face then far face.
std::array<glm::vec3, 8> sliceCorners(const ViewFit& f, float d0, float d1)
{
    const core::Camera& c = f.camera;
    const glm::vec3 right = glm::normalize(glm::cross(c.forward, c.up));
    const float ty = std::tan(0.5f * c.yfovRad), tx = ty * f.aspect;
    std::array<glm::vec3, 8> out;
    for (int k = 0; k < 8; ++k) {
        const float d = k < 4 ? d0 : d1;
        const float sx = (k & 1) ? 1.0f : -1.0f, sy = (k & 2) ? 1.0f : -1.0f;
        out[std::size_t(k)] = c.position + d * (c.forward + sx * tx * right + sy * ty * c.up);
    }
    return out;
}

// The part [t0, t1] of segment a-b inside the box (slabs); false when none.
bool clipToBox(const glm::vec3& a, const glm::vec3& b, const core::Bounds& box, float& t0, float& t1)
{
    t0 = 0.0f;
    t1 = 1.0f;
    const glm::vec3 d = b - a;
    for (int i = 0; i < 3; ++i) {
        if (std::abs(d[i]) < 1e-12f) {
            if (a[i] < box.lo[i] || a[i] > box.hi[i]) return false;
            continue;
        }
        float u0 = (box.lo[i] - a[i]) / d[i], u1 = (box.hi[i] - a[i]) / d[i];
        if (u0 > u1) std::swap(u0, u1);
        t0 = std::max(t0, u0);
        t1 = std::min(t1, u1);
        if (t0 > t1) return false;
    }
    return true;
}

// The part of segment a-b on the inner side of every plane (n . x + w >= 0); false when none.
bool clipToPlanes(const glm::vec3& a, const glm::vec3& b, const std::array<glm::vec4, 6>& planes, float& t0, float& t1)
{
    t0 = 0.0f;
    t1 = 1.0f;
    for (const glm::vec4& p : planes) {
        const float da = glm::dot(glm::vec3(p), a) + p.w, db = glm::dot(glm::vec3(p), b) + p.w;
        if (da < 0.0f && db < 0.0f) return false;
        if (da < 0.0f) t0 = std::max(t0, da / (da - db));
        if (db < 0.0f) t1 = std::min(t1, da / (da - db));
        if (t0 > t1) return false;
    }
    return true;
}

// The vertices of the convex intersection of the frustum slice and the box are among the ends of each
// one's edges clipped to the other: those ends.
std::vector<glm::vec3> sliceBoxPoints(const ViewFit& f, float d0, float d1, const core::Bounds& b)
{
    static const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                     {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    const std::array<glm::vec3, 8> fc = sliceCorners(f, d0, d1);
    std::array<glm::vec3, 8> bc;
    for (int i = 0; i < 8; ++i)
        bc[std::size_t(i)] = {i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z};
    // The slice's planes, normals inwards: a plane through three corners, oriented towards the centroid.
    glm::vec3 centroid(0.0f);
    for (const glm::vec3& c : fc) centroid += c / 8.0f;
    static const int faces[6][3] = {{0, 1, 2}, {4, 5, 6}, {0, 1, 4}, {2, 3, 6}, {0, 2, 4}, {1, 3, 5}};
    std::array<glm::vec4, 6> planes;
    for (int i = 0; i < 6; ++i) {
        const glm::vec3 a = fc[std::size_t(faces[i][0])], p = fc[std::size_t(faces[i][1])];
        const glm::vec3 q = fc[std::size_t(faces[i][2])];
        glm::vec3 n = glm::normalize(glm::cross(p - a, q - a));
        if (glm::dot(n, centroid - a) < 0.0f) n = -n;
        planes[std::size_t(i)] = glm::vec4(n, -glm::dot(n, a));
    }
    std::vector<glm::vec3> points;
    float t0 = 0.0f, t1 = 0.0f;
    for (const auto& e : edges) {
        const glm::vec3 a = fc[std::size_t(e[0])], c = fc[std::size_t(e[1])];
        if (clipToBox(a, c, b, t0, t1)) {
            points.push_back(a + t0 * (c - a));
            points.push_back(a + t1 * (c - a));
        }
        const glm::vec3 ba = bc[std::size_t(e[0])], bb = bc[std::size_t(e[1])];
        if (clipToPlanes(ba, bb, planes, t0, t1)) {
            points.push_back(ba + t0 * (bb - ba));
            points.push_back(ba + t1 * (bb - ba));
        }
    }
    return points;
}

} // namespace

glm::vec2 viewDepthRange(const ViewFit& f, const core::Bounds& b)
{
    float far = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 c(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
        far = std::max(far, glm::dot(c - f.camera.position, f.camera.forward));
    }
    const float near = std::max(f.camera.znear, 1e-4f);
    if (far <= near) return glm::vec2(0.0f);
    glm::vec2 range(std::numeric_limits<float>::max(), 0.0f);
    for (const glm::vec3& p : sliceBoxPoints(f, near, far, b)) {
        const float d = glm::dot(p - f.camera.position, f.camera.forward);
        range = glm::vec2(std::min(range.x, d), std::max(range.y, d));
    }
    return range.y > range.x ? glm::vec2(std::max(range.x, near), range.y) : glm::vec2(0.0f);
}

bool sliceLightRect(const ViewFit& f, float d0, float d1, const core::Bounds& b, const glm::mat4& lightView,
                    glm::vec4& rect)
{
    const std::vector<glm::vec3> points = sliceBoxPoints(f, d0, d1, b);
    if (points.empty()) return false;
    glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : points) {
        const glm::vec2 q(lightView * glm::vec4(p, 1.0f));
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
    rect = glm::vec4(lo, hi);
    return true;
}

float cascadeSplit(float near, float far, int i, int n)
{
    const float t = float(i) / float(n);
    return 0.5f * (near * std::pow(far / near, t) + near + (far - near) * t);
}

namespace {

// The inner sides (n . x + w >= 0, |n| = 1) of the clip volume of viewProj without its far plane (Gribb &
// Hartmann: row 3 plus or minus rows 0, 1, 2).
void appendFrustumPlanes(const glm::mat4& viewProj, std::vector<glm::dvec4>& planes)
{
    const glm::dmat4 rows = glm::transpose(glm::dmat4(viewProj));
    for (const glm::dvec4& p :
         {rows[3] + rows[0], rows[3] - rows[0], rows[3] + rows[1], rows[3] - rows[1], rows[3] + rows[2]}) {
        const double n = glm::length(glm::dvec3(p));
        if (n > 0.0) planes.push_back(p / n);
    }
}

// The vertices of the convex region on the inner side of every plane: the points where three planes meet
// that no plane cuts away (by more than eps). Duplicates where more than three planes meet are harmless to
// the bounding rectangles they feed.
std::vector<glm::dvec3> halfSpaceVertices(const std::vector<glm::dvec4>& planes, double eps)
{
    std::vector<glm::dvec3> out;
    const std::size_t n = planes.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            for (std::size_t k = j + 1; k < n; ++k) {
                const glm::dvec3 a(planes[i]), b(planes[j]), c(planes[k]);
                const glm::dvec3 bc = glm::cross(b, c), ca = glm::cross(c, a), ab = glm::cross(a, b);
                const double det = glm::dot(a, bc);
                if (std::abs(det) < 1e-9) continue; // two of them parallel, or all through one line
                const glm::dvec3 x = -(planes[i].w * bc + planes[j].w * ca + planes[k].w * ab) / det;
                if (std::all_of(planes.begin(), planes.end(),
                                [&](const glm::dvec4& p) { return glm::dot(glm::dvec3(p), x) + p.w >= -eps; }))
                    out.push_back(x);
            }
    return out;
}

// The bounding rectangle's sides, in [-1, 1] units, of the points under viewProj (all in front of it).
glm::dvec2 projectedExtent(const glm::mat4& viewProj, const std::vector<glm::dvec3>& points)
{
    glm::dvec2 lo(1.0), hi(-1.0);
    const glm::dmat4 m(viewProj);
    for (const glm::dvec3& p : points) {
        const glm::dvec4 c = m * glm::dvec4(p, 1.0);
        const glm::dvec2 q = glm::clamp(glm::dvec2(c) / std::max(c.w, 1e-30), -1.0, 1.0);
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
    return glm::max(hi - lo, glm::dvec2(0.0));
}

} // namespace

float footprintSide(const LightView& view, const ViewFit& fit, int height, const core::Bounds& b)
{
    if (b.empty() || height <= 0 || view.orthographic) return 0.0f;
    std::vector<glm::dvec4> planes;
    for (int a = 0; a < 3; ++a) {
        glm::dvec4 lo(0.0), hi(0.0);
        lo[a] = 1.0;
        lo.w = -double(b.lo[a]);
        hi[a] = -1.0;
        hi.w = double(b.hi[a]);
        planes.push_back(lo);
        planes.push_back(hi);
    }
    const glm::mat4 camera = fit.camera.projection(fit.aspect) * fit.camera.view();
    const glm::mat4 light = view.proj * view.view;
    appendFrustumPlanes(camera, planes);
    appendFrustumPlanes(light, planes);
    // A tolerance in metres at the scale of the coordinates involved.
    const double scale = glm::length(glm::dvec3(glm::max(glm::abs(b.lo), glm::abs(b.hi)))) +
                         glm::length(glm::dvec3(fit.camera.position));
    const std::vector<glm::dvec3> region = halfSpaceVertices(planes, 1e-6 * scale + 1e-9);
    if (region.empty()) return 0.0f;
    const glm::dvec2 screen = projectedExtent(camera, region) * 0.5 * glm::dvec2(fit.aspect * height, height);
    const glm::dvec2 covered = glm::max(projectedExtent(light, region) * 0.5, glm::dvec2(1e-6));
    return float(std::sqrt(screen.x * screen.y / (covered.x * covered.y)));
}

LightViews buildLightViews(const std::vector<LightSource>& lights, const core::Bounds& b,
                           const LightViewOptions& options)
{
    LightViews out;
    if (b.empty()) return out; // nothing to see
    out.lightViews.assign(lights.size(), glm::ivec2(0, 0));
    for (int i = 0; i < int(lights.size()); ++i) {
        const LightSource& s = lights[i];
        const int first = int(out.views.size());
        float near = 0.0f, far = 0.0f;
        if (s.type == kLightArea) {
            // The emitting triangles of one mesh share the cube of its centroid (GpuScene keeps them
            // consecutive); later triangles of the mesh point at the first one's cube.
            const auto same = std::find_if(lights.begin(), lights.begin() + i, [&](const LightSource& o) {
                return o.type == kLightArea && o.group == s.group;
            });
            if (same != lights.begin() + i) {
                out.lightViews[i] = out.lightViews[std::size_t(same - lights.begin())];
                continue;
            }
        }
        LightView v;
        v.light = i;
        if (s.type == kLightSpot && s.outerConeRad <= options.maxSingleViewConeRad) {
            lightNearFar(b, s.position, near, far);
            v.fovRad = std::min(2.0f * s.outerConeRad * options.fovMargin, options.maxFovRad);
            v.view = glm::lookAt(s.position, s.position + s.direction, lightUpVector(s.direction));
            v.proj = glm::perspective(v.fovRad, 1.0f, near, far);
            v.origin = s.position;
            v.direction = s.direction;
            v.far = far;
            out.views.push_back(v);
        } else if (s.type == kLightDirectional) {
            const glm::vec3 c = b.centre();
            const float r = std::max(0.5f * glm::length(b.extent()), 1e-3f);
            v.orthographic = true;
            v.orthoHalfExtent = r;
            v.origin = c - s.direction * (2.0f * r);
            v.direction = s.direction;
            v.view = glm::lookAt(v.origin, c, lightUpVector(s.direction));
            v.proj = glm::ortho(-r, r, -r, r, 0.0f, 4.0f * r);
            // Cascades first (the shader takes the first view that holds a point), each fitted to its
            // slice of the camera's frustum and as deep as the whole scene along the light, so that every
            // caster between the sun and the slice is in it. A slice that misses the scene keeps the
            // whole-scene view (the layer count stays put).
            const glm::vec2 depths = options.fit.cascades > 0 ? viewDepthRange(options.fit, b) : glm::vec2(0.0f);
            for (int k = 0; k < options.fit.cascades; ++k) {
                LightView cascade = v;
                glm::vec4 rect;
                if (depths.y > depths.x &&
                    sliceLightRect(options.fit, cascadeSplit(depths.x, depths.y, k, options.fit.cascades),
                                   cascadeSplit(depths.x, depths.y, k + 1, options.fit.cascades), b, v.view, rect)) {
                    const float side = std::max({rect.z - rect.x, rect.w - rect.y, 1e-4f});
                    cascade.orthoHalfExtent = 0.5f * side; // the larger side sets the texel size
                    cascade.proj = glm::ortho(rect.x, rect.z, rect.y, rect.w, 0.0f, 4.0f * r);
                    cascade.cascade = true;
                }
                out.views.push_back(cascade);
            }
            out.views.push_back(v);
        } else {
            if (s.type == kLightArea) {
                v.areaFirst = i;
                while (i + v.areaCount < int(lights.size()) && lights[i + v.areaCount].type == kLightArea &&
                       lights[i + v.areaCount].group == s.group)
                    ++v.areaCount;
            }
            lightNearFar(b, s.position, near, far);
            for (LightView face : cubeViews(s.position, near, far)) {
                face.light = v.light;
                face.areaFirst = v.areaFirst;
                face.areaCount = v.areaCount;
                out.views.push_back(face);
            }
        }
        out.lightViews[i] = glm::ivec2(first, int(out.views.size()) - first);
    }
    return out;
}

} // namespace bounce::gl
