// A ray's hit on the scene (common/raycast.glsl's Hit) decoded into what shading it needs: the point, the
// triangle's geometric and interpolated normals as its mesh has them (not yet turned towards the ray), its
// material, and the BRDF there with the base colour's texel. The photon family's hits: photon tracing
// (photon_trace.comp) and its final gather (photon_gather.glsl). Needs the scene's geometry: a shader that
// includes common/scene.glsl itself defines SCENE_GEOMETRY before it.
#ifndef BOUNCE_SCENE_HIT_GLSL
#define BOUNCE_SCENE_HIT_GLSL

#ifndef SCENE_GEOMETRY
#define SCENE_GEOMETRY
#endif
#include "common/scene.glsl"
#include "common/raycast.glsl"
#include "common/base_color.glsl"
#include "common/material.glsl"

struct SceneHit {
    vec3 p;      // the hit point, barycentric in the triangle's vertices
    vec3 ng;     // unit geometric normal, (p1 - p0) x (p2 - p0)
    vec3 n;      // interpolated shading normal (sceneTriangleNormal)
    Material m;
    BrdfParams b;
};

SceneHit sceneHit(Hit hit)
{
    SceneHit h;
    uint tri = hit.triangle;
    vec3 p0 = sceneVertexPosition(sceneVertexIndex(tri, 0));
    vec3 p1 = sceneVertexPosition(sceneVertexIndex(tri, 1));
    vec3 p2 = sceneVertexPosition(sceneVertexIndex(tri, 2));
    h.p = (1.0 - hit.b.x - hit.b.y) * p0 + hit.b.x * p1 + hit.b.y * p2;
    h.ng = normalize(cross(p1 - p0, p2 - p0));
    h.n = sceneTriangleNormal(tri, hit.b);
    h.m = materials[sceneTriangleMaterial(tri)];
    h.b = materialBrdf(h.m, materialBaseColor(h.m, sceneTriangleUv(tri, hit.b)));
    return h;
}

#endif
