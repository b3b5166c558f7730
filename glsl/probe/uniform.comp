#version 450 core
// Probe: uniform-block words read per second by a compute shader's loop (kernels.glsl: uniformLoop).
#include "probe/kernels.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image2D target;
uniform int count;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(target)))) return;
    imageStore(target, p, uniformLoop(count, vec4(p.xyxy) * 1e-3));
}
