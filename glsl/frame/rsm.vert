#version 450 core
// Reflective shadow map, one light view (Dachsbacher & Stamminger 2005; Nichols et al. 2009 §3.2.2).
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in uint inMaterial;

uniform mat4 viewProj;

out vec3 vPosition;
out vec3 vNormal;
out vec2 vUv;
flat out uint vMaterial;

void main()
{
    vPosition = inPosition;
    vNormal = inNormal;
    vUv = inUv;
    vMaterial = inMaterial;
    gl_Position = viewProj * vec4(inPosition, 1.0);
}
