#version 450 core
// Moving frames' edge antialiasing, first pass (gl/frame/edge_antialias.h): the scene's triangles with their
// neighbours (GpuScene::drawWithAdjacency), from the G-buffer's camera, for the geometry shader to find the
// edges that bound a surface on screen.
layout(location = 0) in vec3 inPosition;

uniform mat4 viewProj;

out vec3 vWorld;

void main()
{
    vWorld = inPosition;
    gl_Position = viewProj * vec4(inPosition, 1.0);
}
