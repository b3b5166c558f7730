// Nearest-photon density estimation (Jensen 2001) in the photon tree: the k photons nearest to x whose
// normals face n, found by walking the heap without a stack (tree_walk.glsl) and skipping every subtree
// farther than the k-th nearest photon found so far (a max-heap of k squared distances). The estimate
// divides their power by the disc pi R^2, R the distance of the k-th. The refinement's "accurate
// irradiance E_p" (section 3.3) and the full photon map's estimate at gather hits (`density=photons`).
// NEAREST_K is k, a compile-time constant: the size of each invocation's heap.
#ifndef BOUNCE_PHOTON_DENSITY_GLSL
#define BOUNCE_PHOTON_DENSITY_GLSL

#include "common/brdf.glsl"
#include "technique/photon/photon_tree.glsl"
#include "technique/photon/tree_walk.glsl"

#ifndef NEAREST_K
#define NEAREST_K 32
#endif

layout(std430, binding = SSBO_PHOTONS) readonly buffer Photons { Photon photons[]; };

struct DensitySums {
    float count;
    vec3 power;        // summed photon power (W)
    float cosWeighted; // summed (w_i . n) Phi_i in luminance: Eq. 3's numerator, for the refinement test
};

// The k nearest photons facing n. The walk is bounded: first by `start`, then, while fewer than k photons
// lie within the bound, by twice the radius (at last by none), so the photons found are exactly the k
// nearest whatever `start` is, and every walk covers a ball of about k photons. Bounds matter: llvmpipe
// ends every loop of an invocation, without a word, once its loops together have run 65,535 iterations
// (gallivm's loop limiter), and an unbounded walk, which fills its heap with far photons first (curve
// order), can take that many. Fewer than k photons in the whole map: all of
// them. radius: the k-th's distance (at least treeMinRadius, so that photons on top of x give a finite
// estimate).
// Where a search for the k nearest photons in a node's region starts: half the radius that holds k of its
// photons at its mean density (lo.w photons within its bounding radius hi.w).
float nearestStartRadius(PhotonNode node)
{
    return 0.5 * node.hi.w * sqrt(float(NEAREST_K) / (kPi * max(node.lo.w, 1.0)));
}

DensitySums nearestPhotons(vec3 x, vec3 n, float start, out float radius)
{
    float nearestD2[NEAREST_K];
    uint nearestIndex[NEAREST_K];
    int size = 0;
    float bound = max(start * start, treeMinRadius * treeMinRadius);
    for (int attempt = 0; attempt < 16 && size < NEAREST_K; ++attempt, bound *= 4.0) {
        if (attempt == 15) bound = 3.0e38;
        size = 0;
        uint i = 1u;
        while (i != 0u) {
            if (!walkToLeafNear(i, x, size == NEAREST_K ? nearestD2[0] : bound)) continue;
            uvec2 range = nodeRange(i);
            for (uint p = range.x; p < range.y; ++p) {
                Photon ph = photons[p];
                float dd = photonDistance2(ph, x);
                if (dd <= (size == NEAREST_K ? nearestD2[0] : bound) && dot(ph.normal.xyz, n) > 0.1) {
                    // Into the max-heap: it grows while it has room, else its largest entry goes.
                    int at = 0;
                    if (size < NEAREST_K) {
                        at = size++;
                        bool up = at > 0;
                        while (up) {
                            int parent = (at - 1) / 2;
                            up = nearestD2[parent] < dd;
                            if (up) {
                                nearestD2[at] = nearestD2[parent];
                                nearestIndex[at] = nearestIndex[parent];
                                at = parent;
                                up = at > 0;
                            }
                        }
                    } else {
                        bool down = true;
                        while (down) {
                            int c = 2 * at + 1;
                            if (c + 1 < NEAREST_K && nearestD2[c + 1] > nearestD2[c]) ++c;
                            down = c < NEAREST_K && nearestD2[min(c, NEAREST_K - 1)] > dd;
                            if (down) {
                                nearestD2[at] = nearestD2[c];
                                nearestIndex[at] = nearestIndex[c];
                                at = c;
                            }
                        }
                    }
                    nearestD2[at] = dd;
                    nearestIndex[at] = p;
                }
            }
            i = skipSubtree(i);
        }
    }
    DensitySums s = DensitySums(float(size), vec3(0.0), 0.0);
    float farthest = 0.0;
    for (int j = 0; j < size; ++j) {
        Photon ph = photons[nearestIndex[j]];
        s.power += ph.powerIndex.rgb;
        s.cosWeighted += max(dot(ph.incoming.xyz, n), 0.0) * photonLuminance(ph.powerIndex.rgb);
        farthest = max(farthest, nearestD2[j]);
    }
    radius = max(sqrt(farthest), treeMinRadius);
    return s;
}

#endif
