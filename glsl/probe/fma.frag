#version 450 core
// Probe: fragment-shader FMA throughput (kernels.glsl).
#include "probe/kernels.glsl"
uniform vec4 a;
uniform vec4 b;
layout(location = 0) out vec4 outValue;
void main()
{
    outValue = fmaChains(gl_FragCoord.xyxy * 1e-3, a, b);
}
