#version 450 core
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in uint inMaterial;

uniform mat4 viewProj;
uniform mat4 view;

out vec3 vNormal;
out vec2 vUv;
out float vEyeDepth;
flat out uint vMaterial;

void main()
{
    vNormal = inNormal;
    vUv = inUv;
    vMaterial = inMaterial;
    vEyeDepth = -(view * vec4(inPosition, 1.0)).z;
    gl_Position = viewProj * vec4(inPosition, 1.0);
}
