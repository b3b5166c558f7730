#version 450 core
// The G-buffer pass: material terms of the one BRDF at each pixel (common/gbuffer.glsl).
#include "common/brdf.glsl"
#include "common/scene.glsl"
#include "common/base_color.glsl"

in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;
in float vEyeDepth;
flat in uint vMaterial;

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outDiffuse;
layout(location = 3) out vec4 outSpecular;
layout(location = 4) out vec4 outEmission;

#ifdef GBUFFER_CONSTANT_FRAGMENT
// Profiling only (frame parameter gbuffer.fragment=constant): no material, no texture.
void main()
{
    outPosition = vec4(0.0, 0.0, 0.0, 1.0);
    outNormal = vec4(0.0, 1.0, 0.0, 1.0);
    outDiffuse = vec4(0.5, 0.5, 0.5, 0.0);
    outSpecular = vec4(0.0);
    outEmission = vec4(0.0, 0.0, 0.0, 1.0);
}
#else
void main()
{
    Material m = materials[vMaterial];
    vec3 n = normalize(vNormal);
    bool doubleSided = m.flags.y != 0;
    vec4 texel = baseColorTexel(m, vUv);
#ifdef ALPHA_MASK
    if (alphaCutOut(m, texel.a)) discard;
#endif
    vec3 baseColor = m.baseColorMetallic.rgb * texel.rgb;
    BrdfParams b = brdfParams(baseColor, m.baseColorMetallic.a, m.emissionRoughness.a, m.specularColorSpecular.a,
                              m.specularColorSpecular.rgb);
    vec3 emission = m.emissionRoughness.rgb;
    if (!gl_FrontFacing) {
        if (doubleSided) {
            n = -n;
        } else {
            // The back of a one-sided surface is black and opaque (as in the reference renderer).
            b.diffuse = vec3(0.0);
            b.weight = 0.0;
            emission = vec3(0.0);
        }
    }
    outPosition = vec4(vPosition, 1.0);
    outNormal = vec4(n, vEyeDepth);
    outDiffuse = vec4(b.diffuse, b.weight);
    outSpecular = vec4(b.f0, m.emissionRoughness.a);
    outEmission = vec4(emission, 1.0);
}
#endif
