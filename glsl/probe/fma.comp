#version 450 core
// Probe: compute-shader FMA throughput (kernels.glsl), one invocation per texel of the target.
#include "probe/kernels.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image2D target;
uniform vec4 a;
uniform vec4 b;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(target)))) return;
    imageStore(target, p, fmaChains(vec4(p.xyxy) * 1e-3 + 0.5e-3, a, b));
}
