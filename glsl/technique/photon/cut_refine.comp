#version 450 core
// One refinement iteration of the illumination cut (section 3.3), one invocation per cut node: a node
// entering the cut gets its accurate irradiance E_p, the standard density estimate from its k nearest
// photons at its middle photon (density.glsl; see below), and the same estimate weighted as Eq. 3 weighs
// photons (by w_i . n_p), which is compared with E~_p. When |E_p - E~_p| > threshold x E~_p (the paper:
// Delta E = 1.2 E~_p) and splitting is allowed, the node leaves the cut and its non-empty children enter
// it. Each invocation writes only its node and its children: no two touch the same node.
// The invocations are the nodes that entered the cut in the last iteration (all of the coarse cut's at
// first), not the whole cut: the others have passed, or are leaves, and have nothing to do. Each writes
// how many children it sent into the cut, for cut_enter.comp, which lists them for the next iteration.
#include "technique/photon/illumination_cut.glsl"
#include "technique/photon/density.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_PHOTON_CUT_LIST) readonly buffer CutList { uint cutList[]; };
layout(std430, binding = SSBO_PHOTON_COUNTERS) buffer Counters { uint counters[]; };
layout(std430, binding = SSBO_SCAN) writeonly buffer Entered { uint entered[]; };

uniform uint listOffset;    // where the entering nodes' list starts in cutList
uniform uint enteringCount; // its length
uniform float threshold; // Delta E over E~_p: 1.2
uniform int split;       // 0: the last pass, which only evaluates
uniform uint iteration;  // the generation children get

void main()
{
    uint c = gl_GlobalInvocationID.x;
    if (c >= enteringCount) return;
    entered[c] = 0u;
    uint i = cutList[listOffset + c];
    PhotonNode node = photonNodes[i];
    uint f = cutFlags(i);
    if (cutNodes[i].irradiance.w == 0.0) {
        // E_p is estimated at the node's middle photon (in curve order), a point on a surface, not at its
        // centre: the photons' mean lies off the surfaces wherever they curve or meet (a corner, a block's
        // edge), and the disc pi R^2 around a point at height h above a surface holds the photons of only
        // pi (R^2 - h^2). As photons grow R shrinks while a node of the coarse cut keeps its size, and the
        // cut lost 5% of the light at 262,144 paths on cornell-spot (README: "The cut's E_p on a surface").
        uvec2 range = nodeRange(i);
        Photon middle = photons[(range.x + range.y) / 2u];
        vec3 x = middle.positionPath.xyz, n = middle.normal.xyz;
        float radius;
        DensitySums s = nearestPhotons(x, n, nearestStartRadius(node), radius);
        float area = kPi * radius * radius;
        float accurate = s.cosWeighted / area;
        float approx = node.power.w;
        float difference = abs(accurate - approx);
        cutNodes[i].irradiance = vec4(s.power / area, 1.0);
        cutNodes[i].normalRatio.w = approx > 0.0 ? difference / approx : (difference == 0.0 ? 0.0 : 3.0e38);
        if (difference <= threshold * approx) f |= kCutPassed;
        setCutFlags(i, f);
    }
    if (split == 0 || (f & kCutPassed) != 0u || nodeIsLeaf(i)) return;
    setCutFlags(i, f & ~kCutIn);
    atomicAdd(counters[kCounterCutSplits], 1u);
    uint children = 0u;
    for (uint child = 2u * i; child <= 2u * i + 1u; ++child) {
        if (photonNodes[child].lo.w <= 0.0) continue;
        setCutFlags(child, cutFlags(child) | kCutIn);
        cutNodes[child].influenceHi.w = float(iteration);
        ++children;
    }
    entered[c] = children;
}
