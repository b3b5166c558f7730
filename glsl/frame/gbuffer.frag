#version 450 core
// The G-buffer pass: eye depth, normal and the material terms of the one BRDF at each pixel, in the layout
// of common/gbuffer.glsl. SCENE_DIFFUSE_ONLY, SCENE_NO_EMITTERS: the scene has no glossy material, no
// emitter, and the frame no such target (Frame::gbufferDefines); NORMAL_MAPS: the scene has normal maps
// and the frame parameter normalMaps is on (frame.cpp, gbufferProgram).
#include "common/brdf.glsl"
#include "common/packing.glsl"
#include "common/scene.glsl"
#include "common/base_color.glsl"
#include "common/material.glsl"
#ifdef NORMAL_MAPS
#include "common/normal_map.glsl"
in vec4 vTangent;
flat in ivec4 vNormalMap;
#endif

in vec3 vNormal;
in vec2 vUv;
in vec3 vEye; // eye-space position (m), on the triangle's plane
// The ray through this pixel's centre in eye space is (gl_FragCoord.xy * eyeRay.xy + eyeRay.zw, -1): the
// ray that common/gbuffer.glsl rebuilds the position along (Frame::renderGBuffer).
uniform vec4 eyeRay;
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

// The eye depth at which the pixel centre's ray meets the triangle's plane. The interpolated depth alone
// is not that: a GPU rasteriser snaps vertices to its sub-pixel grid (1/256 pixel) and interpolates from
// the snapped positions, so the interpolated point lies on the plane but beside the centre's ray; the
// position rebuilt along the ray with that depth then floats off the surface (measured on an NVIDIA H200:
// up to 2.5e-4 of the distance at grazing angles, 60% of the pixels above 1e-5; photon mapping's gather
// rays then started behind their surfaces). The plane is the interpolated point's and its screen
// derivatives'; where they span no plane or the ray grazes it, the interpolated depth.
float eyeDepthOnPlane()
{
    vec3 plane = cross(dFdx(vEye), dFdy(vEye));
    vec3 ray = vec3(gl_FragCoord.xy * eyeRay.xy + eyeRay.zw, -1.0);
    float along = dot(plane, ray), interpolated = -vEye.z;
    float depth = dot(plane, vEye) / along;
    // |cos| of the ray to the plane's normal above 1e-3, compared squared: no square root per fragment.
    bool grazing = !(along * along > 1e-6 * dot(plane, plane) * dot(ray, ray));
    return grazing || !(abs(depth - interpolated) <= 1e-2 * interpolated) ? interpolated : depth;
}

#ifdef GBUFFER_CONSTANT_FRAGMENT
// Profiling only (frame parameter gbuffer.fragment=constant): no material, no texture.
void main()
{
    outGeometry = geometry(-vEye.z, vec3(0.0, 1.0, 0.0));
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
    float eyeDepth = eyeDepthOnPlane(); // before any discard: the derivatives need the whole quad
#ifdef NORMAL_MAPS
    Material m = Material(vBaseColorMetallic, vEmissionRoughness, vSpecularColorSpecular, vFlags, vNormalMap);
    vec3 n = normalMapped(normalize(vNormal), vTangent, vNormalMap, vUv);
#else
    Material m = Material(vBaseColorMetallic, vEmissionRoughness, vSpecularColorSpecular, vFlags, ivec4(-1, 0, 0, 0));
    vec3 n = normalize(vNormal);
#endif
    bool doubleSided = m.flags.y != 0;
    vec4 texel = baseColorTexel(m, vUv);
#ifdef ALPHA_MASK
    if (alphaCutOut(m, texel.a)) discard;
#endif
    vec3 baseColor = m.baseColorMetallic.rgb * texel.rgb;
    BrdfParams b = materialBrdf(m, baseColor);
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
    outGeometry = geometry(eyeDepth, n);
    outDiffuse = vec4(b.diffuse, b.weight);
#ifndef SCENE_DIFFUSE_ONLY
    outSpecular = vec4(b.f0, m.emissionRoughness.a);
#endif
#ifndef SCENE_NO_EMITTERS
    outEmission = vec4(emission, 1.0);
#endif
}
#endif
