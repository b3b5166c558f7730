#include "gl/frame/light_views.h"

#include <algorithm>
#include <cmath>

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
