#version 450 core
// "hierarchy", one dispatch per level, bottom up (§2.1: "we recompute the minimum bounding sphere and cone
// of normals, containing the two child-nodes' bounding spheres and normals ... by successively merging two
// nodes at a time, yielding a total of O(n) operations"): nodes [first, 2 first) from their children.
#include "technique/microrender/hierarchy.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = SSBO_MICRO_NODES) buffer MicroNodes { MicroNode microNodes[]; };
uniform uint first; // 2^level: the level's first node, and its node count

void main()
{
    uint k = gl_GlobalInvocationID.x;
    if (k >= first) return;
    uint i = first + k;
    MicroNode a = microNodes[2u * i], b = microNodes[2u * i + 1u];
    MicroNode n;
    n.sphere = mergeSpheres(a.sphere, b.sphere);
    n.cone = mergeCones(a.cone, b.cone);
    n.areaM2 = a.areaM2 + b.areaM2;
    float wa = n.areaM2 > 0.0 ? a.areaM2 / n.areaM2 : 0.5;
    n.radiance = packRadiance(wa * unpackRadiance(a.radiance) + (1.0 - wa) * unpackRadiance(b.radiance));
    n.pad = 0.0;
#ifdef GLOSSY_POINTS
    n.glossy = mergeGlossy(a.glossy, b.glossy, wa);
#endif
    microNodes[i] = n;
}
