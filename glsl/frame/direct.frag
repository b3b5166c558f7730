#version 450 core
// Direct light as one full-screen pass: emission plus the frame's direct light (lighting.glsl,
// addDirectLight, in the form Frame::directLightDefines chooses for this frame) at every pixel.
#include "common/gbuffer.glsl"
#include "common/lighting.glsl"

uniform vec3 cameraPosition;
uniform vec2 areaRotation; // still frames: this frame's offset of the emitters' glossy points

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
    addDirectLight(radiance, p, n, wo, b, areaRotation);
    outRadiance = vec4(radiance, 1.0);
}
