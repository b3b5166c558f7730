#version 450 core
// E_min (section 3.3): the mean of Eq. 3's estimate over the non-empty nodes of two levels of the photon
// tree (the paper: levels 12-13, where the cut should end up near its target size of 4-8k nodes). One
// work group; each invocation sums a fixed subset in order, then a fixed-order tree reduction: the same
// value in every run.
#include "technique/photon/photon_tree.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = SSBO_PHOTON_COUNTERS) buffer Counters { uint counters[]; };

uniform int firstLevel; // levels firstLevel and firstLevel + 1 (clamped to the tree)

shared float sums[256];
shared float counts[256];

void main()
{
    uint t = gl_LocalInvocationID.x;
    int l0 = clamp(firstLevel, 0, max(treeDepth - 1, 0));
    int l1 = min(l0 + 1, treeDepth);
    uint begin = 1u << uint(l0), end = 2u << uint(l1);
    float s = 0.0, c = 0.0;
    for (uint i = begin + t; i < end; i += 256u) {
        PhotonNode n = photonNodes[i];
        if (n.lo.w > 0.0) {
            s += n.power.w;
            c += 1.0;
        }
    }
    sums[t] = s;
    counts[t] = c;
    barrier();
    for (uint d = 128u; d > 0u; d >>= 1) {
        if (t < d) {
            sums[t] += sums[t + d];
            counts[t] += counts[t + d];
        }
        barrier();
    }
    if (t == 0u) counters[kCounterEmin] = floatBitsToUint(counts[0] > 0.0 ? sums[0] / counts[0] : 0.0);
}
