#version 450 core
// Direct light as one full-screen pass: emission plus every light through the one BRDF, shadowed.
// PUNCTUAL_LIGHTS, AREA_LIGHTS: defined when the scene has lights of that kind.
#include "common/gbuffer.glsl"
#include "common/lighting.glsl"

uniform vec3 cameraPosition;
uniform int punctualLightCount; // lights [0, punctualLightCount): point, spot, directional
uniform int lightCount;         // lights [punctualLightCount, lightCount): emitting triangles

in vec2 vUv;
layout(location = 0) out vec4 outRadiance;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(gPosition, px, 0);
    if (pos.w == 0.0) { outRadiance = vec4(0.0, 0.0, 0.0, 1.0); return; }
    vec3 p = pos.xyz;
    vec3 n = texelFetch(gNormal, px, 0).xyz;
    vec4 diff = texelFetch(gDiffuse, px, 0);
    vec4 spec = texelFetch(gSpecular, px, 0);
    BrdfParams b;
    b.diffuse = diff.rgb;
    b.weight = diff.a;
    b.f0 = spec.rgb;
    b.alpha = max(spec.a * spec.a, 1e-3);
    vec3 wo = normalize(cameraPosition - p);
    vec3 radiance = texelFetch(gEmission, px, 0).rgb;
#ifdef PUNCTUAL_LIGHTS // only the kinds of light the scene has (gl/frame/frame.cpp: directProgram)
    for (int i = 0; i < punctualLightCount; ++i) radiance += directFromPunctual(lights[i], p, n, wo, b);
#endif
#ifdef AREA_LIGHTS
    for (int i = punctualLightCount; i < lightCount; ++i) radiance += directFromAreaTriangle(lights[i], p, n, wo, b);
#endif
    outRadiance = vec4(radiance, 1.0);
}
