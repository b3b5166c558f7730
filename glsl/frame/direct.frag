#version 450 core
// Direct light as one full-screen pass: emission plus every light through the one BRDF, shadowed.
// PUNCTUAL_LIGHTS, AREA_LIGHTS: defined when the scene has lights of that kind; AREA_SAMPLED (still
// frames): the emitters' light from this frame's point on each emitting mesh (lighting.glsl,
// areaSampleUnshadowed) instead of the polygon form factor shadowed from the mesh's centroid.
#include "common/gbuffer.glsl"
#include "common/lighting.glsl"

uniform vec3 cameraPosition;
uniform int punctualLightCount; // lights [0, punctualLightCount): point, spot, directional
uniform int lightCount;         // lights [punctualLightCount, lightCount): emitting triangles
#ifdef AREA_SAMPLED
uniform vec2 areaRotation;      // this frame's offset of the glossy lobe's points
#endif

in vec2 vUv;
layout(location = 0) out vec4 outRadiance;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    GSurface s = gbufferSurface(px);
    if (!s.geometry) { outRadiance = vec4(0.0, 0.0, 0.0, 1.0); return; }
    vec3 p = s.position;
    vec3 n = s.normal;
    BrdfParams b = gbufferBrdf(px);
    vec3 wo = normalize(cameraPosition - p);
    vec3 radiance = gbufferEmission(px);
#ifdef PUNCTUAL_LIGHTS // only the kinds of light the scene has (gl/frame/frame.cpp: directProgram)
    for (int i = 0; i < punctualLightCount; ++i) radiance += directFromPunctual(lights[i], p, n, wo, b);
#endif
#ifdef AREA_LIGHTS
#ifdef AREA_SAMPLED
    radiance += sampledAreaLights(punctualLightCount, lightCount, p, n, wo, b, areaRotation);
#else
    for (int i = punctualLightCount; i < lightCount; ++i) radiance += directFromAreaTriangle(lights[i], p, n, wo, b);
#endif
#endif
    outRadiance = vec4(radiance, 1.0);
}
