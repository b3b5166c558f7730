// The photon map's layouts (gl/technique/photon/photon_tracer.h writes them): photons, the family's
// counters, and the Morton and Hilbert codes the passes share; their random numbers (PCG, radical
// inverses) are common/random.glsl's.
#ifndef BOUNCE_PHOTON_GLSL
#define BOUNCE_PHOTON_GLSL

#include "common/random.glsl"
#include "frame/sort_bindings.glsl"
#include "technique/photon/bindings.glsl"

// A stored photon (Jensen 2001): where it landed, the power it carries (W), the direction it came from
// (unit, pointing away from the surface) and the shading normal of the side it landed on.
struct Photon {
    vec4 positionPath;  // xyz metres, w: the emitting path's index (uint bits)
    vec4 powerIndex;    // rgb W, w: which of the path's stored photons it is (uint bits)
    vec4 incoming;      // xyz unit, towards where the photon came from
    vec4 normal;        // xyz unit
};

// Slots of the counters buffer (PhotonCounters in photon_tracer.h): uints, floats as their bits.
const uint kCounterStaged = 0u;     // photons the tracing wrote (may exceed the capacity)
const uint kCounterStored = 1u;     // photons kept, in order
const uint kCounterScratch = 2u;    // totals of scans nobody reads
const uint kCounterEmin = 3u;       // float: the cut's E_min (section 3.3)
const uint kCounterCutSize = 4u;    // nodes a cut list holds (the compacted cut; in the refinement, those entering it)
const uint kCounterCutSplits = 5u;  // nodes split by the last refinement iteration
const uint kCounterClusters = 6u;   // shading clusters with members
const uint kCounterSeeds = 7u;      // seeds placed
const uint kCounterFirst = 8u;      // free for passes that need one more

// 30-bit Morton code of a point in the box [lo, lo + extent) (10 bits per axis).
uint expandBits10(uint v)
{
    v = (v * 0x00010001u) & 0xFF0000FFu;
    v = (v * 0x00000101u) & 0x0F00F00Fu;
    v = (v * 0x00000011u) & 0xC30C30C3u;
    v = (v * 0x00000005u) & 0x49249249u;
    return v;
}
uint morton30(vec3 p, vec3 lo, vec3 extent)
{
    vec3 q = clamp((p - lo) / max(extent, vec3(1e-30)), vec3(0.0), vec3(0.99999994));
    uvec3 c = uvec3(q * 1024.0);
    return expandBits10(c.x) * 4u + expandBits10(c.y) * 2u + expandBits10(c.z);
}

// 30-bit index along the 3D Hilbert curve of a point in the box [lo, lo + extent) (10 bits per axis;
// Skilling 2004, "Programming the Hilbert curve": the axes to the transposed index, then interleaved).
// Consecutive cells of the Hilbert curve are neighbours, those of the Morton curve are not: a range of
// the Hilbert order is one connected patch, so the photon tree's nodes, ranges of equal counts, get
// compact boxes (Eq. 3's r_p).
uint hilbert30(vec3 p, vec3 lo, vec3 extent)
{
    vec3 q = clamp((p - lo) / max(extent, vec3(1e-30)), vec3(0.0), vec3(0.99999994));
    uvec3 x = uvec3(q * 1024.0);
    for (uint bit = 512u; bit > 1u; bit >>= 1) {
        uint low = bit - 1u;
        for (int i = 0; i < 3; ++i) {
            if ((x[i] & bit) != 0u) {
                x.x ^= low;
            } else {
                uint t = (x.x ^ x[i]) & low;
                x.x ^= t;
                x[i] ^= t;
            }
        }
    }
    x.y ^= x.x;
    x.z ^= x.y;
    uint t = 0u;
    for (uint bit = 512u; bit > 1u; bit >>= 1)
        if ((x.z & bit) != 0u) t ^= bit - 1u;
    x ^= uvec3(t);
    return expandBits10(x.x) * 4u + expandBits10(x.y) * 2u + expandBits10(x.z);
}

float photonLuminance(vec3 c)
{
    return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

#endif
