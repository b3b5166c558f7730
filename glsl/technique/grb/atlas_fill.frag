#version 450 core
// Fills the static atlases at every texel whose centre lies within the fill margin of a triangle
// (core::fillsTexel): llvmpipe has no conservative rasterisation, and a k-buffer fragment or a bilinear
// lookup may land on a texel the triangle only touches. The depth is the distance to the triangle, so a
// texel takes the data of the triangle containing its centre before any neighbour's border. Position and
// normal are the triangle's at the nearest point inside it: every filled texel holds a point of the surface.
#define SCENE_GEOMETRY
#include "common/brdf.glsl"
#include "common/scene.glsl"
#include "technique/grb/atlas.glsl"

layout(binding = UNIT_BASE_COLOR) uniform sampler2DArray baseColorTextures;
layout(std430, binding = SSBO_GRB_TRIANGLE_CHART) readonly buffer TriangleCharts { uint triangleCharts[]; };
uniform float fillMargin;

flat in uint vTriangle;

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outBaseColor;

// Barycentrics (of corners 1 and 2) of the point of triangle abc nearest to q, in the atlas plane.
vec2 nearestBarycentrics(vec2 a, vec2 b, vec2 c, vec2 q, out float dist)
{
    vec2 e1 = b - a, e2 = c - a, r = q - a;
    float det = e1.x * e2.y - e1.y * e2.x;
    if (abs(det) > 1e-12) {
        vec2 w = vec2(r.x * e2.y - r.y * e2.x, e1.x * r.y - e1.y * r.x) / det;
        if (w.x >= 0.0 && w.y >= 0.0 && w.x + w.y <= 1.0) {
            dist = 0.0;
            return w;
        }
    }
    // Outside (or degenerate): the nearest point on the three edges.
    vec2 p[3] = vec2[3](a, b, c);
    vec2 best = vec2(0.0);
    dist = 1e30;
    for (int k = 0; k < 3; ++k) {
        vec2 u = p[k], v = p[(k + 1) % 3], uv = v - u;
        float l2 = dot(uv, uv);
        float s = l2 > 0.0 ? clamp(dot(q - u, uv) / l2, 0.0, 1.0) : 0.0;
        float d = length(q - (u + s * uv));
        if (d < dist) {
            dist = d;
            vec3 bary = vec3(0.0);
            bary[k] = 1.0 - s;
            bary[(k + 1) % 3] = s;
            best = bary.yz;
        }
    }
    return best;
}

void main()
{
    uint t = vTriangle;
    vec2 q = gl_FragCoord.xy;
    float dist;
    vec2 w = nearestBarycentrics(atlasCorner(t, 0), atlasCorner(t, 1), atlasCorner(t, 2), q, dist);
    if (dist > fillMargin) discard;
    gl_FragDepth = dist / (2.0 * fillMargin);

    vec3 p0 = sceneVertexPosition(sceneVertexIndex(t, 0)), p1 = sceneVertexPosition(sceneVertexIndex(t, 1)),
         p2 = sceneVertexPosition(sceneVertexIndex(t, 2));
    vec3 face = cross(p1 - p0, p2 - p0);
    face = dot(face, face) > 0.0 ? normalize(face) : sceneTriangleNormal(t, w);
    vec3 n = sceneTriangleNormal(t, w);
    if (dot(n, face) < 0.0) n = -n; // the shading normal on the front side
    uint material = sceneTriangleMaterial(t);
    vec2 uv = (1.0 - w.x - w.y) * sceneVertexUv(sceneVertexIndex(t, 0)) + w.x * sceneVertexUv(sceneVertexIndex(t, 1)) +
              w.y * sceneVertexUv(sceneVertexIndex(t, 2));
    Material m = materials[material];
    vec3 baseColor = m.baseColorMetallic.rgb;
    if (m.flags.x >= 0) baseColor *= textureLod(baseColorTextures, vec3(uv, float(m.flags.x)), 0.0).rgb;

    outPosition = vec4(sceneTrianglePoint(t, w), float(material) + 1.0);
    outNormal = vec4(n, packFaceNormal(face));
    outBaseColor = vec4(baseColor, float(triangleCharts[t] + 1u));
}
