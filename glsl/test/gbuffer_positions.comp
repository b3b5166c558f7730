#version 450 core
// The G-buffer's positions rebuilt in a compute shader, for the test that every stage rebuilds the same
// bits (tests/gl/frame_test.cpp); Frame::readPositions gives the fragment stage's.
#include "common/gbuffer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) writeonly buffer Positions { vec4 positions[]; };
uniform ivec2 size;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, size))) return;
    GSurface s = gbufferSurface(px);
    positions[px.y * size.x + px.x] = s.geometry ? vec4(s.position, 1.0) : vec4(0.0);
}
