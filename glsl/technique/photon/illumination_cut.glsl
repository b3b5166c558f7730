// The illumination cut (section 3.3; gl/technique/photon/illumination_cut.h): per node of the photon
// tree, whether it is selected, above, in or below the cut, when it entered the cut, its cached
// irradiance E_p, and the box its kernel and those of the cut nodes under it reach (for the gather).
#ifndef BOUNCE_ILLUMINATION_CUT_GLSL
#define BOUNCE_ILLUMINATION_CUT_GLSL

#include "technique/photon/photon_tree.glsl"

struct CutNode {
    vec4 irradiance;   // rgb E_p (W/m^2), the standard density estimate at the node's middle photon (on a
                       // surface; cut_refine.comp); w: 1 once computed
    vec4 influenceLo;  // xyz: the box within which this node's or its cut descendants' kernels (Eq. 5) are non-zero; w: flags (their value)
    vec4 influenceHi;  // xyz; w: the refinement iteration in which the node entered the cut
    vec4 centreRadius; // xyz the node's centre (mean photon position), w: r_p
    vec4 normalRatio;  // xyz n_p, w: |E_p - E~_p| / E~_p, both weighted as Eq. 3 (the refinement test)
    vec4 fallbackLo;   // xyz, w unused: as influence*, for the fallback kernels of twice the radius
    vec4 fallbackHi;
    vec4 incoming;     // xyz the node's photons' mean incoming direction (luminous power weighted), w unused
};

const uint kCutSelected = 1u;   // E~_p > E_min, at a level no deeper than E_min's
const uint kCutAnyBelow = 2u;   // a selected node lies strictly under this one
const uint kCutIn = 4u;         // in the cut
const uint kCutPassed = 8u;     // |E_p - E~_p| <= threshold x E~_p

layout(std430, binding = SSBO_PHOTON_CUT) buffer CutNodes { CutNode cutNodes[]; };

// Flags and generations are small integers held as float values, not as float bits: as bits they would
// be denormals, which a driver that flushes denormals to zero (llvmpipe's vector code, many GPUs) may
// turn into 0 on the way through a register.
uint cutFlags(uint i) { return uint(cutNodes[i].influenceLo.w); }
void setCutFlags(uint i, uint f) { cutNodes[i].influenceLo.w = float(f); }
bool cutSubtreeSelected(uint f) { return (f & (kCutSelected | kCutAnyBelow)) != 0u; }

#endif
