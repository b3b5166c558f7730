#version 450 core
// Probe: fragment-pass bandwidth. Four RGBA32F texels read at the fragment's own pixel, one RGBA32F
// written: 80 bytes per fragment, the shape of a full-screen pass over the G-buffer.
#include "probe/bindings.glsl"
layout(binding = UNIT_PROBE_FIRST) uniform sampler2D in0;
layout(binding = UNIT_PROBE_FIRST + 1) uniform sampler2D in1;
layout(binding = UNIT_PROBE_FIRST + 2) uniform sampler2D in2;
layout(binding = UNIT_PROBE_FIRST + 3) uniform sampler2D in3;
layout(location = 0) out vec4 outValue;
void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    outValue = texelFetch(in0, p, 0) + texelFetch(in1, p, 0) + texelFetch(in2, p, 0) + texelFetch(in3, p, 0);
}
