#version 450 core
// The cut's compaction, step 1: one mark per node of the cut, to be scanned into list positions.
#include "technique/photon/illumination_cut.glsl"
#include "technique/photon/linear_dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_SCAN) writeonly buffer Marks { uint marks[]; };

uniform uint nodeCount;

void main()
{
    uint i = linearInvocation();
    if (i >= nodeCount) return;
    marks[i] = (i > 0u && (cutFlags(i) & kCutIn) != 0u) ? 1u : 0u;
}
