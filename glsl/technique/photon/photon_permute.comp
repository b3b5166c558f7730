#version 450 core
// sorted[i] = photons[order[i]]: the photons in Morton order, after the radix sort of their codes.
#include "technique/photon/photon.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_PHOTONS) readonly buffer Photons { Photon photons[]; };
layout(std430, binding = SSBO_SORT_VALUES) readonly buffer Order { uint order[]; };
layout(std430, binding = SSBO_PHOTON_STAGING) writeonly buffer Sorted { Photon sorted[]; };

uniform uint count;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    sorted[i] = photons[order[i]];
}
