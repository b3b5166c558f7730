#version 450 core
// Direct light as one full-screen pass: emission plus the frame's direct light (lighting.glsl,
// addDirectLight, in the form Frame::directLightDefines chooses for this frame) at every pixel.
#include "common/gbuffer.glsl"
#include "common/lighting.glsl"

uniform vec3 cameraPosition;
uniform vec2 areaRotation; // still frames: this frame's offset of the emitters' glossy points

in vec2 vUv;
layout(location = 0) out vec4 outRadiance;
#ifdef AREA_RATIO
// Moving frames with temporal.direct (common/lighting.glsl, areaLightsRatio): the emitting triangles' exact
// unshadowed light, and this frame's sums of w V and w, which the temporal reuse averages over the frames.
layout(location = 1) out vec4 outAreaUnshadowed;
layout(location = 2) out vec4 outAreaVisibility;
#endif

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    GSurface s = gbufferSurface(px);
#ifdef AREA_RATIO
    outAreaUnshadowed = vec4(0.0);
    outAreaVisibility = vec4(0.0, 0.0, 0.0, 1.0);
#endif
    if (!s.geometry) { outRadiance = vec4(0.0, 0.0, 0.0, 1.0); return; }
    vec3 p = s.position;
    vec3 n = s.normal;
    BrdfParams b = gbufferBrdf(px);
    vec3 wo = normalize(cameraPosition - p);
    vec3 radiance = gbufferEmission(px);
    addDirectLight(radiance, p, n, wo, b, areaRotation);
#ifdef AREA_RATIO
    vec3 unshadowed;
    vec2 visibility;
    areaLightsRatio(punctualLightCount, lightCount, p, n, wo, b, unshadowed, visibility);
    outAreaUnshadowed = vec4(unshadowed, 1.0);
    outAreaVisibility = vec4(visibility, 0.0, 1.0);
#endif
    outRadiance = vec4(radiance, 1.0);
}
