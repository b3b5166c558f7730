#version 450 core
// Exclusive prefix sum of `count` uints, in place, and their total: the compaction step of the photon
// family (photon offsets per path, the cut list, digit offsets of the radix sort, cluster members). One
// work group of 1024 invocations, each summing a contiguous run, then a scan of the 1024 run sums in
// shared memory (Hillis and Steele 1986). Integer sums: the same result in any order of execution.
#include "technique/photon/bindings.glsl"
layout(local_size_x = 1024) in;

layout(std430, binding = SSBO_PHOTON_SCAN) buffer ScanData { uint scanData[]; };
layout(std430, binding = SSBO_PHOTON_COUNTERS) buffer Counters { uint counters[]; };

uniform uint count;
uniform uint totalSlot; // counters[totalSlot] receives the total

shared uint runSums[1024];

void main()
{
    uint t = gl_LocalInvocationID.x;
    uint run = (count + 1023u) / 1024u;
    uint begin = min(t * run, count);
    uint end = min(begin + run, count);
    uint sum = 0u;
    for (uint i = begin; i < end; ++i) sum += scanData[i];
    runSums[t] = sum;
    barrier();
    for (uint d = 1u; d < 1024u; d <<= 1) {
        uint left = t >= d ? runSums[t - d] : 0u;
        barrier();
        runSums[t] += left;
        barrier();
    }
    uint index = runSums[t] - sum;
    for (uint i = begin; i < end; ++i) {
        uint v = scanData[i];
        scanData[i] = index;
        index += v;
    }
    if (t == 1023u) counters[totalSlot] = runSums[1023];
}
