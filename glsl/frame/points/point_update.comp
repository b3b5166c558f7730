#version 450 core
// "point-update": every point's surfel from its (triangle, barycentrics) on the scene as it is now
// (micro-rendering §2.1, "Deforming and Moving Geometry"; point projection §4 "Scene Points": "we simply
// update them using their bary coords"): position, interpolated normal, and the diffuse colour of its
// material times its base-colour texture at the interpolated uv, as the G-buffer computes it, and
// (GLOSSY_POINTS) the glossy lobe's F0 and roughness.
#define SCENE_GEOMETRY
#include "common/brdf.glsl"
#include "common/scene.glsl"
#include "common/material.glsl"
#define POINT_SAMPLES
#define POINT_SURFELS
#define POINT_GLOSSY
#include "frame/points/point_cloud.glsl"

layout(local_size_x = 64) in;
layout(binding = UNIT_BASE_COLOR) uniform sampler2DArray baseColorTextures;
uniform uint pointCount;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= pointCount) return;
    PointSample s = pointSamples[i];
    uint tri = s.triangle;
    vec2 b = s.barycentrics;
    Material m = materials[sceneTriangleMaterial(tri)];
    vec3 baseColor = m.baseColorMetallic.rgb;
#ifdef TEXTURES
    if (m.flags.x >= 0) {
        vec2 uv = sceneTriangleUv(tri, b);
        baseColor *= textureLod(baseColorTextures, vec3(uv, float(m.flags.x)), 0.0).rgb;
    }
#endif
    BrdfParams p = materialBrdf(m, baseColor);
    PointSurfel o;
    o.position = sceneTrianglePoint(tri, b);
    // "Under deformations we scale the points' radii to compensate for the varying point densities"
    // (micro-rendering §2.1): the points of a triangle share its area as it is now.
    o.areaM2 = s.triangleShare * sceneTriangleArea(tri);
    o.normal = sceneTriangleNormal(tri, b);
    // The fourth byte: the glossy lobe's weight w (point_light.comp folds it into the glossy irradiance).
    o.diffuse = packUnorm4x8(vec4(clamp(p.diffuse, 0.0, 1.0), clamp(p.weight, 0.0, 1.0)));
    pointSurfels[i] = o;
#ifdef GLOSSY_POINTS
    pointGlossy[i].w = packGlossyMaterial(p.f0, p.alpha);
#endif
}
