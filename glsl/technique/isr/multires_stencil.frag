#version 450 core
// §3.2.1, one-pass stencil refinement: drawn once over the whole flattened multiresolution buffer with
// stencil op REPLACE; every fragment that is not a valid multiresolution fragment is discarded, so the
// stencil ends up set at exactly the valid ones (common/multires.glsl: fragmentValid). Valid
// fragments are also counted per level (one atomic add each: they are few, and the count costs no pass),
// and each marks which neighbours the upsampling may interpolate with (multires.glsl: sameSurfaceNeighbours).
#include "technique/isr/bindings.glsl"
#include "common/multires.glsl"

layout(std430, binding = SSBO_ISR_FRAGMENT_COUNTS) buffer FragmentCounts { uint fragmentCounts[]; };

// Alpha of the illumination buffer: 1 + the mask of same-surface neighbours for the upsampling (the
// gather writes rgb only). Fragments that are not valid keep the cleared 0.
layout(location = 0) out vec4 outMarks;

void main()
{
    int level;
    ivec2 t;
    // "if (for all i, f not in MipmapLevel(i)) continue": texels of the flattened image outside every level.
    if (!locateInFlattened(ivec2(gl_FragCoord.xy), level, t)) discard;
    if (!fragmentValid(level, t)) discard;
    atomicAdd(fragmentCounts[level], 1u);
    outMarks = vec4(0.0, 0.0, 0.0, 1.0 + float(sameSurfaceNeighbours(level, t)));
}
