// §3.2.2's gather at one multiresolution fragment: the VPLs of the current block of the VPL cache summed
// at its patch's mean position and normal, WITHOUT the receiver's diffuse colour:
//   E_i = 1/pi sum_j rho_j Phi_j cos_i cos_j / (pi r^2 + A_j)        (Eqs. 1 and 5 divided by rho_i)
// The upsampling multiplies by the full-resolution rho_i, so albedo (texture) detail inside a coarse patch
// survives and a patch straddling two colours is not averaged. Shared by the gather's two forms:
// multires_gather.frag (the paper's stenciled quad) and multires_gather.comp (the listed valid fragments).
#ifndef BOUNCE_CACHE_GATHER_GLSL
#define BOUNCE_CACHE_GATHER_GLSL

#include "common/multires.glsl"
#include "technique/isr/vpl.glsl"

uniform int vplCount; // VPLs of this draw's block (vpl.glsl: vplBlock)

vec3 cacheGather(ivec2 at)
{
    int level;
    ivec2 t;
    vec3 sum = vec3(0.0);
    if (!locateInFlattened(at, level, t)) return sum;
    MultiresPatch p = loadPatch(level, t);
    float len = length(p.normal);
    // A patch whose pixels are all black reflects nothing: skip its gather (its result is multiplied by 0).
    if (len > 0.0 && max(p.diffuse.r, max(p.diffuse.g, p.diffuse.b)) > 0.0) {
        vec3 n = p.normal / len;
        for (int j = 0; j < vplCount; ++j) sum += vplContribution(vplBlock[j], p.position, n, vec3(1.0));
    }
    return sum;
}

#endif
