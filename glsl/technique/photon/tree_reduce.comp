#version 450 core
// One level of the photon tree from the level below: every sum is its children's (photon_tree.glsl).
#include "technique/photon/photon_tree.glsl"
#include "technique/photon/tree_level.glsl"

void main()
{
    uint i = levelNode();
    if (i == 0u) return;
    PhotonNode a = photonNodes[2u * i], b = photonNodes[2u * i + 1u];
    PhotonNode n;
    n.lo = vec4(min(a.lo.xyz, b.lo.xyz), a.lo.w + b.lo.w);
    n.hi = vec4(max(a.hi.xyz, b.hi.xyz), 0.0);
    n.power = vec4(a.power.rgb + b.power.rgb, 0.0);
    n.position = a.position + b.position;
    n.normal = vec4(a.normal.xyz + b.normal.xyz, 0.0);
    n.incoming = vec4(a.incoming.xyz + b.incoming.xyz, 0.0);
    finishNode(n);
    photonNodes[i] = n;
}
