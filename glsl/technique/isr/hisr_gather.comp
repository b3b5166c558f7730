#version 450 core
// Hierarchical image-space radiosity, the gather (§3.5.1) as a compute pass over the valid multiresolution
// fragments of the list multires_valid_list.comp made: the same walk as the stenciled quad of
// hisr_gather.frag (hisr_walk.glsl), added into the flattened buffer's rgb (each fragment's texel is
// written by one invocation; alpha keeps the stencil pass's marks). Departure from the paper's one quad,
// for drivers with few graphics units (MultiresGather::gatherAsFragments): on an NVIDIA H100 a fragment
// pass reached 1.8 TFLOP/s and a compute pass 46 (bounce probe).
//
// HISR_LANES invocations share one fragment (a power of two up to 64), each walking every HISR_LANES-th
// top patch, and the first adds their sums in lane order (the same sum in every run). The valid fragments
// are few (28,310 at 1024x768 on the Cornell box): with one invocation each, a GPU has a few warps per
// multiprocessor to hide the walk's dependent tree fetches; with 16 it is full.
#include "technique/isr/hisr_walk.glsl"
#include "technique/isr/valid_list.glsl"

shared vec3 laneSum[64];
shared uint laneGathered[64];

void main()
{
    uint lid = gl_LocalInvocationIndex;
    uint lane = lid % uint(HISR_LANES);
    ivec2 at;
    bool listed = listedFragmentAt(listInvocation() / uint(HISR_LANES), at);
    uint gathered = 0u;
    vec3 sum = listed ? hisrGather(at, int(lane), HISR_LANES, gathered) : vec3(0.0);
    laneSum[lid] = sum;
    laneGathered[lid] = gathered;
    barrier();
    if (!listed || lane != 0u) return;
    for (uint i = 1u; i < uint(HISR_LANES); ++i) {
        sum += laneSum[lid + i];
        gathered += laneGathered[lid + i];
    }
    hisrCount(gathered);
    addToFragment(at, sum);
}
