#version 450 core
// VPL tree, level `level` >= 1 from level - 1 (§3.5; technique/isr/vpl_tree.glsl): each cluster sums its
// four children's reflected flux, solid angle and area, takes their area-weighted mean position and
// normal (not renormalised, so that means of means stay area-weighted; the gather normalises), and the
// min and max of their light distances (the max is |V_j| of Eqs. 7-8, conservative over the patch).
// A cluster spans a light-space discontinuity (a departure, after §3.3-3.4's discontinuity-aware light
// patches) when a child does, when its relative light-distance range (max - min) / min exceeds
// lightDepthThreshold, or when its lit normals diverge: 1 - |mean of the unit normals| > lightNormalThreshold
// (0 for equal normals; two normals at an angle theta give 1 - cos(theta / 2)). The flag is stored as
// the sign of the cluster's |V_j| (vpl_tree.glsl), so that the gather decides on three texels.
#include "technique/isr/vpl_tree.glsl"

#include "technique/isr/bindings.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = SSBO_ISR_VPL_TREE) buffer VplTree { VplNode tree[]; };

uniform int level;
uniform int subtreeCount;
uniform float lightDepthThreshold;
uniform float lightNormalThreshold;

void main()
{
    int perSubtree = 1 << (2 * (treeDepth - level)); // nodes of this level in one subtree
    int id = int(gl_GlobalInvocationID.x);
    if (id >= perSubtree * subtreeCount) return;
    int subtree = id / perSubtree, code = id - subtree * perSubtree;
    int base = subtree * treeSubtreeNodes;
    int firstChild = base + treeLevelOffset[level - 1] + 4 * code;

    vec3 position = vec3(0.0), normal = vec3(0.0), flux = vec3(0.0);
    float area = 0.0, omega = 0.0, distance = 0.0, nearest = 1e30;
    bool discontinuous = false;
    for (int i = 0; i < 4; ++i) {
        VplNode c = tree[firstChild + i];
        float a = c.positionArea.w;
        position += a * c.positionArea.xyz;
        normal += a * c.normal.xyz;
        area += a;
        distance = max(distance, abs(c.normal.w));
        nearest = min(nearest, c.range.x);
        discontinuous = discontinuous || c.normal.w < 0.0;
        flux += c.flux.rgb;
        omega += c.flux.w;
    }
    vec3 meanNormal = area > 0.0 ? normal / area : vec3(0.0);
    if (nearest < 1e30 && distance - nearest > lightDepthThreshold * nearest) discontinuous = true;
    if (area > 0.0 && 1.0 - length(meanNormal) > lightNormalThreshold) discontinuous = true;
    VplNode node;
    node.positionArea = vec4(area > 0.0 ? position / area : vec3(0.0), area);
    node.normal = vec4(meanNormal, discontinuous ? -distance : distance);
    node.range = vec4(nearest, 0.0, 0.0, 0.0);
    node.flux = vec4(flux, omega);
    tree[base + treeLevelOffset[level] + code] = node;
}
