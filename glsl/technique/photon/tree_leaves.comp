#version 450 core
// The photon tree's leaves: one invocation per leaf sums its photons (photon_tree.glsl).
#include "technique/photon/photon_tree.glsl"
#include "technique/photon/linear_dispatch.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_PHOTONS) readonly buffer Photons { Photon photons[]; };

void main()
{
    uint k = linearInvocation();
    uint leaves = 1u << uint(treeDepth);
    if (k >= leaves) return;
    uint i = leaves + k;
    uvec2 range = nodeRange(i);
    PhotonNode n = emptyNode();
    for (uint p = range.x; p < range.y; ++p) {
        Photon ph = photons[p];
        float lum = photonLuminance(ph.powerIndex.rgb);
        n.lo.xyz = min(n.lo.xyz, ph.positionPath.xyz);
        n.hi.xyz = max(n.hi.xyz, ph.positionPath.xyz);
        n.lo.w += 1.0;
        n.power.rgb += ph.powerIndex.rgb;
        n.position += vec4(ph.positionPath.xyz, lum);
        n.normal.xyz += ph.normal.xyz * lum;
        n.incoming.xyz += ph.incoming.xyz * lum;
    }
    finishNode(n);
    photonNodes[i] = n;
}
