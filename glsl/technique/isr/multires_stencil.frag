#version 450 core
// §3.2.1, one-pass stencil refinement with stencil op REPLACE; every fragment that is not a valid
// multiresolution fragment is discarded, so the stencil ends up set at exactly the valid ones
// (common/multires.glsl: fragmentValid), and each valid one marks which neighbours the upsampling may
// interpolate with (multires.glsl: sameSurfaceNeighbours). Drawn level by level over the flattened buffer
// (gl/technique/isr/multires_gather.h: a departure), so the level is the draw's and the texels outside every
// level ("if (for all i, f not in MipmapLevel(i)) continue") are never drawn; an occlusion query per level
// counts the valid fragments.
#include "common/multires.glsl"

uniform int drawLevel; // the level this draw covers

// Alpha of the illumination buffer: 1 + the mask of same-surface neighbours for the upsampling (the
// gather writes rgb only). Fragments that are not valid keep the cleared 0.
layout(location = 0) out vec4 outMarks;

void main()
{
    ivec2 t = ivec2(gl_FragCoord.xy) - levelOrigin[drawLevel];
    if (!fragmentValid(drawLevel, t)) discard;
    outMarks = vec4(0.0, 0.0, 0.0, 1.0 + float(sameSurfaceNeighbours(drawLevel, t)));
}
