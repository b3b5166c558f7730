#version 450 core
// hilbert30 (technique/photon/photon.glsl) of points from a buffer, for the tests of the photon order.
#include "technique/photon/photon.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 1) writeonly buffer Keys { uint keys[]; };
uniform uint pointCount;
uniform vec3 boundsLo;
uniform vec3 boundsExtent;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= pointCount) return;
    keys[i] = hilbert30(points[i].xyz, boundsLo, boundsExtent);
}
