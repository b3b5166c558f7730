#version 450 core
// Probe: fragment-shader texel fetch rate (kernels.glsl).
#include "probe/kernels.glsl"
layout(binding = UNIT_PROBE_FIRST) uniform sampler2D small;
layout(location = 0) out vec4 outValue;
void main()
{
    outValue = fetchUnrolled(small, ivec2(gl_FragCoord.xy));
}
