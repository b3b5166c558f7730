#version 450 core
// The first bounce's seed (the paper's Fig. 11 hybrid, Sec. 6.5): the diffuse direct light of point, spot
// and directional lights at every atlas texel, through the frame's shadow maps, stored per unit albedo
// as radiance.glsl says: sum over lights of t(cos) E / pi. Emitting surfaces need no seed: the bundles
// carry their light (Sec. 5.1).
#include "common/lighting.glsl"
#include "common/material.glsl"
#include "technique/grb/atlas.glsl"

layout(location = 0) out vec4 outSeed;

void main()
{
    ivec2 t = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(atlasPosition, t, 0);
    if (pos.w == 0.0) discard;
    vec3 n = texelFetch(atlasNormal, t, 0).xyz;
    Material m = materials[uint(pos.w) - 1u];
    BrdfParams b = materialBrdf(m, texelFetch(atlasBaseColor, t, 0).rgb);
    vec3 seed = vec3(0.0);
    for (int i = 0; i < punctualLightCount; ++i) {
        vec3 wi;
        vec3 e = punctualIrradiance(frameLight(i), pos.xyz, n, wi);
        if (max(e.r, max(e.g, e.b)) > 0.0)
            seed += brdfTransmission(b, max(dot(n, wi), 0.0)) * e * shadowVisibility(frameLight(i), pos.xyz, n) / kPi;
    }
    outSeed = vec4(seed, 1.0);
}
