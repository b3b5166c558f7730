#version 450 core
// Probe: uniform-block words read per second by a fragment shader's loop (kernels.glsl: uniformLoop).
#include "probe/kernels.glsl"
uniform int count;
layout(location = 0) out vec4 outValue;
void main()
{
    outValue = uniformLoop(count, gl_FragCoord.xyxy * 1e-3);
}
