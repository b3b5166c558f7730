#version 450 core
// The area lights' ratio estimator, resolved (Frame::resolveAreaRatio; common/lighting.glsl,
// areaLightsRatio): the emitting triangles' exact unshadowed light times the visible share of it, the
// temporal reuse's mean of w V over its mean of w, added to the direct light by the blend (one, one).
// Where no frame of the history drew a point p faces (w = 0: the emitter beyond p's horizon in every frame
// it holds), the share is 1: the exact light unshadowed.
#include "common/bindings.glsl"

layout(binding = UNIT_AREA_UNSHADOWED) uniform sampler2D areaUnshadowed;
layout(binding = UNIT_AREA_VISIBILITY) uniform sampler2D areaVisibility;

layout(location = 0) out vec4 outRadiance;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 unshadowed = texelFetch(areaUnshadowed, px, 0).rgb;
    vec2 v = texelFetch(areaVisibility, px, 0).rg;
    float share = v.y > 0.0 ? clamp(v.x / v.y, 0.0, 1.0) : 1.0;
    outRadiance = vec4(unshadowed * share, 0.0);
}
