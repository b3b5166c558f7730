#version 450 core
// "gather-select": the valid fragments of the frame's multiresolution buffer (common/multires.glsl: a
// patch without discontinuity whose parent has one) listed for the gather, with the mask of same-surface
// neighbours the upsampling may interpolate with. The list's order follows thread timing, but each
// target's result depends on its own texel only, so the image does not.
#include "common/multires.glsl"
#include "frame/points/bindings.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
// The list's length, counted up here, then its targets (frame/points/bindings.glsl, SSBO_GATHER_TARGETS).
layout(std430, binding = SSBO_GATHER_TARGETS) buffer GatherTargets { uint gatherCount; uint gatherPad; uvec2 gatherTargets[]; };
uniform ivec2 flattenedSize;

void main()
{
    ivec2 a = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(a, flattenedSize))) return;
    int level;
    ivec2 t;
    if (!locateInFlattened(a, level, t) || !fragmentValid(level, t)) return;
    uint k = atomicAdd(gatherCount, 1u);
    gatherTargets[k] = uvec2(uint(a.x) | (uint(a.y) << 16), sameSurfaceNeighbours(level, t) | (uint(level) << 16));
}
