#version 450 core
// The coarse cut made valid (section 3.3: "deleting nodes whose children are already in the cut, and
// adding nodes to cover leaf nodes that do not have parents representing them"): a selected node with
// no selected node under it stays; a node with nothing selected in its subtree is added when its parent
// has a selection under it (it is the top of a region nothing covers), or when it is the root. Every
// root-to-leaf path then meets exactly one cut node. Empty nodes cover nothing and are left out.
#include "technique/photon/illumination_cut.glsl"
#include "technique/photon/linear_dispatch.glsl"

layout(local_size_x = 64) in;

uniform uint nodeCount; // 2^(depth + 1)

void main()
{
    uint i = linearInvocation();
    if (i == 0u || i >= nodeCount) return;
    uint f = cutFlags(i);
    bool keep = (f & kCutSelected) != 0u && (f & kCutAnyBelow) == 0u;
    bool cover = !cutSubtreeSelected(f) && (i == 1u || (cutFlags(i >> 1) & kCutAnyBelow) != 0u);
    if ((keep || cover) && photonNodes[i].lo.w > 0.0) setCutFlags(i, f | kCutIn);
}
