#version 450 core
// One level of the cut's selection, bottom-up (section 3.3): a node no deeper than the levels E_min
// comes from is selected when its estimate exceeds E_min, and learns whether a selected node lies under
// it (from its children, done before). Also resets what the refinement writes.
//
// Why no deeper: Eq. 3 is a density, and on a surface lit evenly its expectation is the same at every
// level (a node of half the photons has half the area), while over the few photons of a node near the
// leaves their box shrinks faster than their count and E~_p grows. Selected at every level, a region lit
// above the mean keeps its deepest selected nodes, the leaves: the cut then holds about one node per
// photon wherever the light is above average, and its size follows the photon count. The paper picks
// E_min at levels 12-13 so that "the initial illumination cut should be close to its target size,
// 4K-8K": the coarse cut lies at and above those levels, brighter regions reaching them and dimmer ones
// staying above, and only the refinement goes deeper.
#include "technique/photon/illumination_cut.glsl"
#include "technique/photon/tree_level.glsl"

layout(std430, binding = SSBO_PHOTON_COUNTERS) readonly buffer Counters { uint counters[]; };

uniform int lastLevel; // the deeper of E_min's two levels

void main()
{
    uint i = levelNode();
    if (i == 0u) return;
    PhotonNode n = photonNodes[i];
    float eMin = uintBitsToFloat(counters[kCounterEmin]);
    uint f = (level <= lastLevel && n.lo.w > 0.0 && n.power.w > eMin) ? kCutSelected : 0u;
    if (level < treeDepth && (cutSubtreeSelected(cutFlags(2u * i)) || cutSubtreeSelected(cutFlags(2u * i + 1u))))
        f |= kCutAnyBelow;
    cutNodes[i].irradiance = vec4(0.0);
    cutNodes[i].influenceLo = vec4(vec3(3.0e38), float(f));
    cutNodes[i].influenceHi = vec4(vec3(-3.0e38), 0.0);
    cutNodes[i].centreRadius = vec4(nodeCentre(n), n.hi.w);
    cutNodes[i].normalRatio = vec4(nodeNormal(n), 0.0);
    float len = length(n.incoming.xyz);
    cutNodes[i].incoming = vec4(len > 0.0 ? n.incoming.xyz / len : nodeNormal(n), 0.0);
}
