#version 450 core
// Hierarchical image-space radiosity, the gather (§3.5.1) as a compute pass: one invocation per valid
// multiresolution fragment of the list multires_valid_list.comp made, the same walk as the stenciled
// quad of hisr_gather.frag (hisr_walk.glsl), added into the flattened buffer's rgb (each invocation owns
// its texel; alpha keeps the stencil pass's marks). Departure from the paper's one quad, for drivers with
// few graphics units (MultiresGather::gatherAsFragments): on an NVIDIA H100 a fragment pass reached 1.8
// TFLOP/s and a compute pass 46 (bounce probe).
#include "technique/isr/hisr_walk.glsl"
#include "technique/isr/valid_list.glsl"

layout(local_size_x = 64) in;

void main()
{
    ivec2 at;
    if (!listedFragment(at)) return;
    uint gathered;
    vec3 sum = hisrGather(at, gathered);
    hisrCount(gathered);
    addToFragment(at, sum);
}
