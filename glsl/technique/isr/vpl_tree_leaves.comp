#version 450 core
// VPL tree, level 0 (§3.5; technique/isr/vpl_tree.glsl): every RSM texel becomes a leaf, its VPL exactly
// as rsm-full makes it (position, normal, reflected flux, solid angle, area A_t = omega_t |V_t|^2, Eq. 3),
// plus its light distance |V_t| for the refinement bound. Unlit texels keep zero flux and area.
#include "technique/isr/bindings.glsl"
#include "common/rsm.glsl"
#include "technique/isr/vpl_tree.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = SSBO_ISR_VPL_TREE) writeonly buffer VplTreeOut { VplNode treeOut[]; };

uniform int rsmSize;

void main()
{
    ivec2 x = ivec2(gl_GlobalInvocationID.xy);
    int view = int(gl_GlobalInvocationID.z);
    if (x.x >= rsmSize || x.y >= rsmSize) return;
    int patchSide = rsmSize / treeTopGrid;
    ivec2 top = x / patchSide;
    int subtree = (view * treeTopGrid + top.y) * treeTopGrid + top.x;
    int index = subtree * treeSubtreeNodes + treeLevelOffset[0] + mortonCode(x - top * patchSide);

    vec4 p = texelFetch(rsmPosition, ivec3(x, view), 0);
    vec4 n = texelFetch(rsmNormal, ivec3(x, view), 0);
    vec4 f = texelFetch(rsmFlux, ivec3(x, view), 0);
    float distance = 0.0;
    if (p.w != 0.0) {
        RsmView v = rsmViews[view];
        distance = v.originOrtho.w != 0.0 ? dot(p.xyz - v.originOrtho.xyz, v.directionTexel.xyz)
                                          : length(p.xyz - v.originOrtho.xyz);
    }
    VplNode node;
    node.positionArea = vec4(p.xyz, n.w);
    node.normal = vec4(n.xyz, distance);
    node.flux = f;
    node.range = vec4(p.w != 0.0 ? distance : 1e30, 0.0, 0.0, 0.0);
    treeOut[index] = node;
}
