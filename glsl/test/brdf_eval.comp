#version 450 core
// Evaluates glsl/common/brdf.glsl on inputs from a buffer, for the C++/GLSL agreement test.
#include "common/brdf.glsl"

layout(local_size_x = 64) in;

struct BrdfCase {
    vec4 baseColorMetallic;
    vec4 specularColorSpecular;
    vec4 nRoughness;
    vec4 wo;
    vec4 wi;
};
layout(std430, binding = 0) readonly buffer Cases { BrdfCase cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform uint caseCount;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= caseCount) return;
    BrdfCase c = cases[i];
    BrdfParams p = brdfParams(c.baseColorMetallic.rgb, c.baseColorMetallic.a, c.nRoughness.w, c.specularColorSpecular.a,
                              c.specularColorSpecular.rgb);
    results[i] = vec4(brdfEval(p, c.nRoughness.xyz, c.wo.xyz, c.wi.xyz), 0.0);
}
