#version 450 core
// §3.2.2, the stenciled gather: one full-screen quad over the flattened multiresolution buffer with the
// stencil test EQUAL, so only valid fragments run (early stencil culling). Each sums the VPLs of one
// uniform block of the VPL cache per draw (additive; cache_gather.glsl). Writes rgb only (alpha holds
// the stencil pass's marks).
#include "technique/isr/cache_gather.glsl"

layout(early_fragment_tests) in;

layout(location = 0) out vec4 outIllumination;

void main()
{
    outIllumination = vec4(cacheGather(ivec2(gl_FragCoord.xy)), 0.0); // alpha is masked off: the marks stay
}
