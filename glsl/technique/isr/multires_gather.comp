#version 450 core
// §3.2.2's gather as a compute pass: one invocation per valid fragment of the list multires_valid_list.comp
// made, the same sum as the stenciled quad (cache_gather.glsl), added into the flattened buffer's rgb
// (each invocation owns its texel; alpha keeps the stencil pass's marks). Departure from the paper's one
// quad for GPUs whose graphics units are few (MultiresGather::gatherAsFragments).
#include "technique/isr/cache_gather.glsl"
#include "technique/isr/valid_list.glsl"

void main()
{
    ivec2 at;
    if (listedFragment(at)) addToFragment(at, cacheGather(at));
}
