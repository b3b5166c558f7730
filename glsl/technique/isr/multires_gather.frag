#version 450 core
// §3.2.2, the stenciled gather: one full-screen quad over the flattened multiresolution buffer with the
// stencil test EQUAL, so only valid fragments run (early stencil culling). Each sums the VPLs of the
// VPL cache at its patch's mean position and normal, one uniform block of the cache per draw (additive). Written WITHOUT the receiver's diffuse colour:
//   E_i = 1/pi sum_j rho_j Phi_j cos_i cos_j / (pi r^2 + A_j)        (Eqs. 1 and 5 divided by rho_i)
// The upsampling multiplies by the full-resolution rho_i, so albedo (texture) detail inside a coarse patch
// survives and a patch straddling two colours is not averaged. Writes rgb only (alpha holds the
// stencil pass's marks).
#include "common/multires.glsl"
#include "technique/isr/vpl.glsl"

layout(early_fragment_tests) in;

uniform int vplCount; // VPLs of this draw's block (vpl.glsl: vplBlock)

layout(location = 0) out vec4 outIllumination;

void main()
{
    int level;
    ivec2 t;
    vec3 sum = vec3(0.0);
    if (locateInFlattened(ivec2(gl_FragCoord.xy), level, t)) {
        MultiresPatch p = loadPatch(level, t);
        float len = length(p.normal);
        // A patch whose pixels are all black reflects nothing: skip its gather (its result is multiplied by 0).
        if (len > 0.0 && max(p.diffuse.r, max(p.diffuse.g, p.diffuse.b)) > 0.0) {
            vec3 n = p.normal / len;
            for (int j = 0; j < vplCount; ++j) sum += vplContribution(vplBlock[j], p.position, n, vec3(1.0));
        }
    }
    outIllumination = vec4(sum, 0.0); // alpha is masked off: the stencil pass's marks stay
}
