#version 450 core
// Every scene triangle rasterised along one global ray-bundle (Sec. 4.2), pulled from the scene's
// buffers with its atlas corners: no depth test, no culling, each fragment one hit point of one ray.
#define SCENE_GEOMETRY
#include "common/scene.glsl"
#include "technique/grb/atlas.glsl"
#include "technique/grb/bundle.glsl"

uniform mat4 bundleViewProj; // orthographic, the jitter included (bundle_directions.h)

out vec2 vAtlas;
out float vDepth;
#ifdef ALPHA_MASK
flat out uint vTriangle;
out vec2 vUv;
#endif

void main()
{
    uint t = uint(gl_VertexID) / 3u;
    int c = gl_VertexID % 3;
    vec3 p = sceneVertexPosition(sceneVertexIndex(t, c));
    vAtlas = atlasCorner(t, c);
    vDepth = bundleDepth(p);
#ifdef ALPHA_MASK
    vTriangle = t;
    vUv = sceneVertexUv(sceneVertexIndex(t, c));
#endif
    gl_Position = bundleViewProj * vec4(p, 1.0);
}
