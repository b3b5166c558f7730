#version 450 core
// The cut's compaction, step 2: every cut node writes its index at its scanned position: the cut list,
// in heap order (the same list in every run).
#include "technique/photon/illumination_cut.glsl"
#include "technique/photon/linear_dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_SCAN) readonly buffer Positions { uint positions[]; };
layout(std430, binding = SSBO_PHOTON_CUT_LIST) writeonly buffer CutList { uint cutList[]; };

uniform uint nodeCount;

void main()
{
    uint i = linearInvocation();
    if (i == 0u || i >= nodeCount) return;
    if ((cutFlags(i) & kCutIn) != 0u) cutList[positions[i]] = i;
}
