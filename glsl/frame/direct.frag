#version 450 core
// Direct light as one full-screen pass: emission plus every light through the one BRDF, shadowed.
#include "common/gbuffer.glsl"
#include "common/lighting.glsl"

uniform vec3 cameraPosition;
uniform int lightCount;

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
    for (int i = 0; i < lightCount; ++i) radiance += directFromLight(lights[i], p, n, wo, b);
    outRadiance = vec4(radiance, 1.0);
}
