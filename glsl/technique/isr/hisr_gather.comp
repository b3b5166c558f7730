#version 450 core
// Hierarchical image-space radiosity, the gather (§3.5.1) as a compute pass over the valid multiresolution
// fragments of the list multires_valid_list.comp made: the same walk as the stenciled quad of
// hisr_gather.frag (hisr_walk.glsl), added into the flattened buffer's rgb (each fragment's texel is
// written by one invocation; alpha keeps the stencil pass's marks). Departure from the paper's one quad,
// for drivers with few graphics units (MultiresGather::gatherAsFragments): on an NVIDIA H100 a fragment
// pass reached 1.8 TFLOP/s and a compute pass 46 (bounce probe).
//
// `lanes` invocations share one fragment (a power of two up to 64), each walking every lanes-th top patch,
// and the first adds their sums in lane order (the same sum in every run). The valid fragments may be too
// few to fill a GPU with one invocation each (28,310 at 1024x768 on the Cornell box): more lanes hide the
// walk's dependent tree fetches, but the lanes of one fragment fetch different nodes, where neighbouring
// fragments in a warp share theirs (hisrGatherLanes chooses, gatherLanes=auto).
#include "technique/isr/hisr_walk.glsl"
#include "technique/isr/valid_list.glsl"

uniform int lanes;

shared vec3 laneSum[64];
shared uint laneGathered[64];

void main()
{
    uint lid = gl_LocalInvocationIndex;
    uint lane = lid % uint(lanes);
    ivec2 at;
    bool listed = listedFragmentAt(listInvocation() / uint(lanes), at);
    uint gathered = 0u;
    vec3 sum = listed ? hisrGather(at, int(lane), lanes, gathered) : vec3(0.0);
    laneSum[lid] = sum;
    laneGathered[lid] = gathered;
    barrier();
    if (!listed || lane != 0u) return;
    for (uint i = 1u; i < uint(lanes); ++i) {
        sum += laneSum[lid + i];
        gathered += laneGathered[lid + i];
    }
    hisrCount(gathered);
    addToFragment(at, sum);
}
