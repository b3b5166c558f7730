// Virtual point lights of image-space radiosity (Nichols, Shopf & Wyman 2009, §3.2.2): the VPL cache every
// gathering pass reads, and the contribution of one VPL to one receiver (Eqs. 1 and 5).
#ifndef BOUNCE_ISR_VPL_GLSL
#define BOUNCE_ISR_VPL_GLSL

#include "technique/isr/bindings.glsl"

struct Vpl {
    vec4 positionArea;   // xyz world position (m), w: A_j, the patch area (m^2), Eq. 3
    vec4 normal;         // xyz unit normal N_j, w: hierarchy level (0 = one RSM texel)
    vec4 flux;           // rgb rho_j Phi_j: flux reflected by the patch (W), w: solid angle omega_j (sr)
};

// The gathers read the cache through this uniform block: VPL_BLOCK_SIZE consecutive VPLs of it, one block
// per draw or dispatch (gl/technique/isr/vpl_gather.h: bindVplBlock). Every invocation reads the same VPL
// at the same time, the pattern uniform blocks serve best: a GPU broadcasts it from its constant cache,
// and llvmpipe loads it without the per-lane loop it runs for every SSBO load (3x faster gathers here).
// The passes that write the cache bind it as an SSBO (vpl_write.glsl).
#ifdef VPL_BLOCK_SIZE
layout(std140, binding = UBO_ISR_VPL_BLOCK) uniform VplBlock { Vpl vplBlock[VPL_BLOCK_SIZE]; };
#endif

// Outgoing radiance at receiver i (position p, normal n, diffuse colour rho_i) from VPL j, Eqs. 1 and 5
// in radiometric units: with B_j = rho_j Phi_j / A_j the patch radiosity and the disk-to-point form factor
// F = A_j cos_i cos_j / (pi r^2 + A_j), L_i = rho_i / pi * B_j F = rho_i / pi * rho_j Phi_j cos_i cos_j / (pi r^2 + A_j).
// The + A_j term keeps it finite when the VPL sits on the receiver (r -> 0). No visibility (Eq. 1).
// Evaluated without a square root: with d = x_j - x_i, cos_i = N_i.d / r and cos_j = -N_j.d / r, so
// cos_i cos_j / (pi r^2 + A_j) = (N_i.d)(-N_j.d) / (r^2 (pi r^2 + A_j)), one division. The numerator is at
// most r^2, so the quotient stays below 1 / A_j; at r = 0 both are 0 and the floor on the denominator
// gives 0 (the direction to a VPL on the receiver is undefined; its neighbourhood is what the + A_j bounds).
vec3 vplContribution(Vpl v, vec3 p, vec3 n, vec3 rho)
{
    const float kPi = 3.14159265358979323846;
    vec3 d = v.positionArea.xyz - p;
    float r2 = dot(d, d);
    float cosI = max(dot(n, d), 0.0);            // cos_i r
    float cosJ = max(-dot(v.normal.xyz, d), 0.0); // cos_j r
    float denominator = max(kPi * r2 * (kPi * r2 + v.positionArea.w), 1.17549435e-38); // 1/pi of Eq. 5 included
    return rho * v.flux.rgb * (cosI * cosJ / denominator);
}

#endif
