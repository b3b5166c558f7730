// Virtual point lights of image-space radiosity (Nichols, Shopf & Wyman 2009, §3.2.2): the VPL cache every
// gathering pass reads, and the contribution of one VPL to one receiver (Eqs. 1 and 5).
#ifndef BOUNCE_ISR_VPL_GLSL
#define BOUNCE_ISR_VPL_GLSL

struct Vpl {
    vec4 positionArea;   // xyz world position (m), w: A_j, the patch area (m^2), Eq. 3
    vec4 normal;         // xyz unit normal N_j, w: hierarchy level (0 = one RSM texel)
    vec4 flux;           // rgb rho_j Phi_j: flux reflected by the patch (W), w: solid angle omega_j (sr)
};

#ifndef VPL_BINDING
#define VPL_BINDING 8
#endif
layout(std430, binding = VPL_BINDING) readonly buffer VplCache { Vpl vpls[]; };

// Outgoing radiance at receiver i (position p, normal n, diffuse colour rho_i) from VPL j, Eqs. 1 and 5
// in radiometric units: with B_j = rho_j Phi_j / A_j the patch radiosity and the disk-to-point form factor
// F = A_j cos_i cos_j / (pi r^2 + A_j), L_i = rho_i / pi * B_j F = rho_i / pi * rho_j Phi_j cos_i cos_j / (pi r^2 + A_j).
// The + A_j term keeps it finite when the VPL sits on the receiver (r -> 0). No visibility (Eq. 1).
vec3 vplContribution(Vpl v, vec3 p, vec3 n, vec3 rho)
{
    vec3 d = v.positionArea.xyz - p;
    float r2 = dot(d, d);
    float r = sqrt(r2);
    vec3 w = r > 0.0 ? d / r : n;
    float cosI = max(dot(n, w), 0.0);
    float cosJ = max(dot(v.normal.xyz, -w), 0.0);
    return rho * (1.0 / 3.14159265358979323846) * v.flux.rgb * (cosI * cosJ / (3.14159265358979323846 * r2 + v.positionArea.w));
}

#endif
