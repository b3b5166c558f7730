#version 450 core
// The scene from the camera, each triangle carrying its atlas corners, to look up the atlas at every
// pixel (Sec. 3: "display").
#define SCENE_GEOMETRY
#include "common/scene.glsl"
#include "technique/grb/atlas.glsl"

uniform mat4 viewProj;

out vec2 vAtlas;

void main()
{
    uint t = uint(gl_VertexID) / 3u;
    int c = gl_VertexID % 3;
    vAtlas = atlasCorner(t, c);
    gl_Position = viewProj * vec4(sceneVertexPosition(sceneVertexIndex(t, c)), 1.0);
}
