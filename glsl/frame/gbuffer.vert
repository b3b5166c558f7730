#version 450 core
// The G-buffer pass's vertices. The material is read here, once per vertex, and handed to the fragments
// as flat inputs: a fragment shader that indexes the material buffer by a per-fragment value loads it
// lane by lane on a SIMD rasteriser (llvmpipe: 2.2 of the pass's 6 ms at 512x512 on cornell-spot).
#include "common/scene.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in uint inMaterial;
#ifdef NORMAL_MAPS
layout(location = 4) in vec4 inTangent; // zero on meshes without tangents (gl/frame/gpu_scene.h)
out vec4 vTangent;
flat out ivec4 vNormalMap;
#endif

uniform mat4 viewProj;
uniform mat4 view;

out vec3 vNormal;
out vec2 vUv;
out vec3 vEye; // eye-space position (m)
flat out vec4 vBaseColorMetallic;
flat out vec4 vEmissionRoughness;
flat out vec4 vSpecularColorSpecular;
flat out ivec4 vFlags;

void main()
{
    vNormal = inNormal;
    vUv = inUv;
    Material m = materials[inMaterial];
    vBaseColorMetallic = m.baseColorMetallic;
    vEmissionRoughness = m.emissionRoughness;
    vSpecularColorSpecular = m.specularColorSpecular;
    vFlags = m.flags;
#ifdef NORMAL_MAPS
    vTangent = inTangent;
    vNormalMap = m.normalMap;
#endif
    vEye = (view * vec4(inPosition, 1.0)).xyz;
    gl_Position = viewProj * vec4(inPosition, 1.0);
}
