#version 450 core
// The valid fragments of the flattened multiresolution buffer as a list, for a gather that runs as a
// compute pass (hisr_gather.comp): every texel whose alpha the stencil pass marked (1 + its neighbour
// mask; 0 elsewhere) appends its coordinates, x | y << 16. The list's order follows the atomics and
// differs from run to run; each entry's result does not.
#include "technique/isr/bindings.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform readonly image2D illumination;
layout(std430, binding = SSBO_ISR_VALID_LIST) buffer ValidList { uint validCount; uint validFragments[]; };

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(illumination)))) return;
    if (imageLoad(illumination, p).a > 0.0) validFragments[atomicAdd(validCount, 1u)] = uint(p.x) | (uint(p.y) << 16);
}
