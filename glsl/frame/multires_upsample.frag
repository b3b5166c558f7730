#version 450 core
// The upsampling (frame/multires_upsample.glsl) as a full-screen fragment pass into the frame's indirect
// texture: what a software rasteriser runs best (llvmpipe stores a compute pass's images lane by lane).
#include "frame/multires_upsample.glsl"

layout(location = 0) out vec4 outIndirect;

void main()
{
    outIndirect = vec4(upsampled(ivec2(gl_FragCoord.xy)), 1.0);
}
