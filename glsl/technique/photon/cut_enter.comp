#version 450 core
// The nodes a refinement iteration sent into the cut, listed for the next (cut_refine.comp): a node that
// split (it has left the cut) writes its non-empty children, in heap order, at its scanned position. The
// list keeps its parents' order: the same list in every run.
#include "technique/photon/illumination_cut.glsl"
#include "technique/photon/linear_dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_SCAN) readonly buffer Positions { uint positions[]; };
layout(std430, binding = SSBO_PHOTON_CUT_LIST) buffer CutList { uint cutList[]; };

uniform uint listOffset;    // the last iteration's entering nodes
uniform uint enteringCount;
uniform uint nextOffset;    // where their children go

void main()
{
    uint c = linearInvocation();
    if (c >= enteringCount) return;
    uint i = cutList[listOffset + c];
    if ((cutFlags(i) & kCutIn) != 0u) return; // it stayed
    uint at = nextOffset + positions[c];
    for (uint child = 2u * i; child <= 2u * i + 1u; ++child)
        if (photonNodes[child].lo.w > 0.0) cutList[at++] = child;
}
