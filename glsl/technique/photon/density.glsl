// Nearest-photon density estimation (Jensen 2001) in the photon tree: the photons within a sphere of
// radius R around x whose normals face n, found by walking the heap without a stack (skipSubtree), and
// R grown until it holds k photons. The refinement's "accurate irradiance E_p" (section 3.3).
#ifndef BOUNCE_PHOTON_DENSITY_GLSL
#define BOUNCE_PHOTON_DENSITY_GLSL

#include "common/brdf.glsl"
#include "technique/photon/illumination_cut.glsl"

layout(std430, binding = SSBO_PHOTONS) readonly buffer Photons { Photon photons[]; };

struct DensitySums {
    float count;
    vec3 power;        // summed photon power (W)
    float cosWeighted; // summed (w_i . n) Phi_i in luminance: Eq. 3's numerator, for the 1.2x test
};

DensitySums photonsWithin(vec3 x, vec3 n, float radius)
{
    DensitySums s = DensitySums(0.0, vec3(0.0), 0.0);
    float r2 = radius * radius;
    uint i = 1u;
    while (i != 0u) {
        PhotonNode node = photonNodes[i];
        if (node.lo.w <= 0.0 || boxDistance(x, node.lo.xyz, node.hi.xyz) > radius) {
            i = skipSubtree(i);
        } else if (nodeIsLeaf(i)) {
            uvec2 range = nodeRange(i);
            for (uint p = range.x; p < range.y; ++p) {
                Photon ph = photons[p];
                vec3 d = ph.positionPath.xyz - x;
                if (dot(d, d) <= r2 && dot(ph.normal.xyz, n) > 0.1) {
                    s.count += 1.0;
                    s.power += ph.powerIndex.rgb;
                    s.cosWeighted += max(dot(ph.incoming.xyz, n), 0.0) * photonLuminance(ph.powerIndex.rgb);
                }
            }
            i = skipSubtree(i);
        } else {
            i = 2u * i;
        }
    }
    return s;
}

// The estimate from about k nearest photons: R starts where node `start` (whose photons surround x)
// would hold k at its mean density, and grows by half until k photons are inside (at most 12 times).
// Returns the sums and the radius they were taken over.
DensitySums nearestPhotons(vec3 x, vec3 n, PhotonNode start, float k, out float radius)
{
    radius = start.hi.w * sqrt(k / (kPi * max(start.lo.w, 1.0)));
    DensitySums s = photonsWithin(x, n, radius);
    for (int step = 0; step < 12 && s.count < k; ++step) {
        radius *= 1.5;
        s = photonsWithin(x, n, radius);
    }
    return s;
}

#endif
