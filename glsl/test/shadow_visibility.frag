#version 450 core
// shadowVisibility (common/shadow.glsl) of light `lightIndex` at every G-buffer pixel, -1 on the
// background: the gathered PCF, or with SHADOW_PCF_TAPS the filtered taps (tests/gl/shadow_pcf_test.cpp).
#include "common/gbuffer.glsl"
#include "common/shadow.glsl"

uniform int lightIndex;

layout(location = 0) out vec4 outVisibility;

void main()
{
    GSurface s = gbufferSurface(ivec2(gl_FragCoord.xy));
    outVisibility = vec4(s.geometry ? shadowVisibility(frameLight(lightIndex), s.position, s.normal) : -1.0);
}
