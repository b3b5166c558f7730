#version 450 core
// One level of the cut's selection, bottom-up (section 3.3): a node is selected when its estimate
// exceeds E_min, and learns whether a selected node lies under it (from its children, done before).
// Also resets what the refinement writes.
#include "technique/photon/illumination_cut.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_PHOTON_COUNTERS) readonly buffer Counters { uint counters[]; };

uniform int level;

void main()
{
    uint k = gl_GlobalInvocationID.x;
    if (k >= (1u << uint(level))) return;
    uint i = (1u << uint(level)) + k;
    PhotonNode n = photonNodes[i];
    float eMin = uintBitsToFloat(counters[kCounterEmin]);
    uint f = (n.lo.w > 0.0 && n.power.w > eMin) ? kCutSelected : 0u;
    if (level < treeDepth && (cutSubtreeSelected(cutFlags(2u * i)) || cutSubtreeSelected(cutFlags(2u * i + 1u))))
        f |= kCutAnyBelow;
    cutNodes[i].irradiance = vec4(0.0);
    cutNodes[i].influenceLo = vec4(vec3(3.0e38), uintBitsToFloat(f));
    cutNodes[i].influenceHi = vec4(vec3(-3.0e38), uintBitsToFloat(0u));
    cutNodes[i].centreRadius = vec4(nodeCentre(n), n.hi.w);
    cutNodes[i].normalRatio = vec4(nodeNormal(n), 0.0);
    float len = length(n.incoming.xyz);
    cutNodes[i].incoming = vec4(len > 0.0 ? n.incoming.xyz / len : nodeNormal(n), 0.0);
}
