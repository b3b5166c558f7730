#version 450 core
layout(location = 0) in vec3 inPosition;
uniform mat4 viewProj;
#ifdef ALPHA_MASK
// Scenes with alpha-masked materials: the fragment shader cuts their holes (shadow.frag).
layout(location = 2) in vec2 inUv;
layout(location = 3) in uint inMaterial;
out vec2 vUv;
flat out uint vMaterial;
#endif
void main()
{
#ifdef ALPHA_MASK
    vUv = inUv;
    vMaterial = inMaterial;
#endif
    gl_Position = viewProj * vec4(inPosition, 1.0);
}
