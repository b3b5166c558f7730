#version 450 core
// The G-buffer pass: eye depth, normal and the material terms of the one BRDF at each pixel, in the layout
// of common/gbuffer.glsl. SCENE_DIFFUSE_ONLY, SCENE_NO_EMITTERS: the scene has no glossy material, no
// emitter, and the frame no such target (Frame::gbufferDefines).
#include "common/brdf.glsl"
#include "common/packing.glsl"
#include "common/scene.glsl"
#include "common/base_color.glsl"

in vec3 vNormal;
in vec2 vUv;
in float vEyeDepth;
flat in vec4 vBaseColorMetallic; // the triangle's material (gbuffer.vert)
flat in vec4 vEmissionRoughness;
flat in vec4 vSpecularColorSpecular;
flat in ivec4 vFlags;

layout(location = 0) out uvec2 outGeometry;
layout(location = 1) out vec4 outDiffuse;
#ifndef SCENE_DIFFUSE_ONLY
layout(location = 2) out vec4 outSpecular;
#endif
#ifndef SCENE_NO_EMITTERS
layout(location = 3) out vec4 outEmission;
#endif

// Eye depth as float bits: never 0 in front of the camera (0 marks the background).
uvec2 geometry(float eyeDepth, vec3 n) { return uvec2(floatBitsToUint(max(eyeDepth, 1e-30)), packUnitVector(n)); }

#ifdef GBUFFER_CONSTANT_FRAGMENT
// Profiling only (frame parameter gbuffer.fragment=constant): no material, no texture.
void main()
{
    outGeometry = geometry(vEyeDepth, vec3(0.0, 1.0, 0.0));
    outDiffuse = vec4(0.5, 0.5, 0.5, 0.0);
#ifndef SCENE_DIFFUSE_ONLY
    outSpecular = vec4(0.0);
#endif
#ifndef SCENE_NO_EMITTERS
    outEmission = vec4(0.0, 0.0, 0.0, 1.0);
#endif
}
#else
void main()
{
    Material m = Material(vBaseColorMetallic, vEmissionRoughness, vSpecularColorSpecular, vFlags);
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
    outGeometry = geometry(vEyeDepth, n);
    outDiffuse = vec4(b.diffuse, b.weight);
#ifndef SCENE_DIFFUSE_ONLY
    outSpecular = vec4(b.f0, m.emissionRoughness.a);
#endif
#ifndef SCENE_NO_EMITTERS
    outEmission = vec4(emission, 1.0);
#endif
}
#endif
