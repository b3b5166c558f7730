#version 450 core
layout(location = 0) in vec3 inPosition;
uniform mat4 viewProj;
void main() { gl_Position = viewProj * vec4(inPosition, 1.0); }
