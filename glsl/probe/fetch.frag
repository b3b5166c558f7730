#version 450 core
// Probe: fragment-shader texel fetch rate (kernels.glsl).
#include "probe/bindings.glsl"
#include "probe/kernels.glsl"
layout(binding = UNIT_PROBE_FIRST) uniform sampler2D small;
uniform int fetches;
layout(location = 0) out vec4 outValue;
void main()
{
    outValue = fetchLoop(small, ivec2(gl_FragCoord.xy), fetches);
}
