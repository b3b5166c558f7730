#version 450 core
// Puts the traced photons in path order (each path's photons in the order it stored them) from the
// exclusive prefix sum of the per-path counts, and writes each one's Hilbert index over the scene's bounds
// with its index: the keys and values the radix sort orders the photon tree by (section 3.1, Zhou et al.
// 2008 build their kd-tree over the same points; we sort by Hilbert index and build a linear hierarchy).
#include "technique/photon/photon.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_PHOTON_STAGING) readonly buffer Staging { Photon staging[]; };
layout(std430, binding = SSBO_PHOTON_PATHS) readonly buffer PathOffsets { uint pathOffsets[]; };
layout(std430, binding = SSBO_PHOTONS) writeonly buffer Photons { Photon photons[]; };
layout(std430, binding = SSBO_SORT_KEYS) writeonly buffer Keys { uint keys[]; };
layout(std430, binding = SSBO_SORT_VALUES) writeonly buffer Values { uint values[]; };

uniform uint count;
uniform vec3 boundsLo;
uniform vec3 boundsExtent;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    Photon ph = staging[i];
    uint dst = pathOffsets[floatBitsToUint(ph.positionPath.w)] + floatBitsToUint(ph.powerIndex.w);
    photons[dst] = ph;
    keys[dst] = hilbert30(ph.positionPath.xyz, boundsLo, boundsExtent);
    values[dst] = dst;
}
