#version 450 core
// Probe: compute-pass buffer bandwidth. One vec4 read from one SSBO and written to another: 32 bytes.
#include "probe/bindings.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = SSBO_PROBE_SOURCE) readonly buffer Source { vec4 source[]; };
layout(std430, binding = SSBO_PROBE_TARGET) writeonly buffer Target { vec4 target[]; };
uniform uint count;
void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    target[i] = source[i] * 0.5;
}
