#version 450 core
// Probe: compute-shader texel fetch rate (kernels.glsl).
#include "probe/kernels.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = UNIT_PROBE_FIRST) uniform sampler2D small;
layout(rgba32f, binding = 0) uniform writeonly image2D target;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(target)))) return;
    imageStore(target, p, fetchUnrolled(small, p));
}
