// Nearest-photon density estimation (Jensen 2001) in the photon tree: the k photons nearest to x whose
// normals face n, found by walking the heap without a stack (skipSubtree) and skipping every subtree
// farther than the k-th nearest photon found so far (a max-heap of k squared distances). The estimate
// divides their power by the disc pi R^2, R the distance of the k-th. The refinement's "accurate
// irradiance E_p" (section 3.3) and the full photon map's estimate at gather hits (`density=photons`).
// NEAREST_K is k, a compile-time constant; each invocation's heap lives in shared memory, NEAREST_K
// entries per invocation of a work group of NEAREST_GROUP (on a GPU an array private to an invocation and
// indexed by a variable goes to slow local memory).
#ifndef BOUNCE_PHOTON_DENSITY_GLSL
#define BOUNCE_PHOTON_DENSITY_GLSL

#include "common/brdf.glsl"
#include "technique/photon/illumination_cut.glsl"

#ifndef NEAREST_K
#define NEAREST_K 32
#endif
#ifndef NEAREST_GROUP
#define NEAREST_GROUP 64
#endif

shared float nearestD2[NEAREST_GROUP * NEAREST_K];
shared uint nearestIndex[NEAREST_GROUP * NEAREST_K];

layout(std430, binding = SSBO_PHOTONS) readonly buffer Photons { Photon photons[]; };

struct DensitySums {
    float count;
    vec3 power;        // summed photon power (W)
    float cosWeighted; // summed (w_i . n) Phi_i in luminance: Eq. 3's numerator, for the refinement test
};

// Puts (dd, p) into the max-heap of `size` entries at `base`: while it has room it grows, else its
// largest entry is replaced.
void heapInsert(uint base, inout int size, float dd, uint p)
{
    int at = 0;
    if (size < NEAREST_K) {
        at = size++;
        bool up = at > 0;
        while (up) {
            int parent = (at - 1) / 2;
            up = nearestD2[base + uint(parent)] < dd;
            if (up) {
                nearestD2[base + uint(at)] = nearestD2[base + uint(parent)];
                nearestIndex[base + uint(at)] = nearestIndex[base + uint(parent)];
                at = parent;
                up = at > 0;
            }
        }
    } else {
        bool down = true;
        while (down) {
            int c = 2 * at + 1;
            if (c + 1 < NEAREST_K && nearestD2[base + uint(c + 1)] > nearestD2[base + uint(c)]) ++c;
            down = c < NEAREST_K && nearestD2[base + uint(min(c, NEAREST_K - 1))] > dd;
            if (down) {
                nearestD2[base + uint(at)] = nearestD2[base + uint(c)];
                nearestIndex[base + uint(at)] = nearestIndex[base + uint(c)];
                at = c;
            }
        }
    }
    nearestD2[base + uint(at)] = dd;
    nearestIndex[base + uint(at)] = p;
}

// The k nearest photons facing n. The walk is bounded: first by `start`, then, while fewer than k photons
// lie within the bound, by twice the radius (at last by none), so the photons found are exactly the k
// nearest whatever `start` is, and every walk covers a ball of about k photons. Bounds matter: llvmpipe
// ends a loop after 65535 iterations without a word, and an unbounded walk, which fills its heap with
// far photons first (Morton order), can take that many. Fewer than k photons in the whole map: all of
// them. radius: the k-th's distance (at least treeMinRadius, so that photons on top of x give a finite
// estimate).
DensitySums nearestPhotons(vec3 x, vec3 n, float start, out float radius)
{
    const uint base = gl_LocalInvocationIndex * uint(NEAREST_K);
    int size = 0;
    float bound = max(start * start, treeMinRadius * treeMinRadius);
    for (int attempt = 0; attempt < 16 && size < NEAREST_K; ++attempt, bound *= 4.0) {
        if (attempt == 15) bound = 3.0e38;
        size = 0;
        uint i = 1u;
        while (i != 0u) {
            PhotonNode node = photonNodes[i];
            float limit = size == NEAREST_K ? nearestD2[base] : bound;
            if (node.lo.w <= 0.0 || boxDistance2(x, node.lo.xyz, node.hi.xyz) > limit) {
                i = skipSubtree(i);
            } else if (!nodeIsLeaf(i)) {
                i = 2u * i;
            } else {
                uvec2 range = nodeRange(i);
                for (uint p = range.x; p < range.y; ++p) {
                    Photon ph = photons[p];
                    vec3 d = ph.positionPath.xyz - x;
                    float dd = dot(d, d);
                    if (dd <= (size == NEAREST_K ? nearestD2[base] : bound) && dot(ph.normal.xyz, n) > 0.1)
                        heapInsert(base, size, dd, p);
                }
                i = skipSubtree(i);
            }
        }
    }
    DensitySums s = DensitySums(float(size), vec3(0.0), 0.0);
    float farthest = 0.0;
    for (int j = 0; j < size; ++j) {
        Photon ph = photons[nearestIndex[base + uint(j)]];
        s.power += ph.powerIndex.rgb;
        s.cosWeighted += max(dot(ph.incoming.xyz, n), 0.0) * photonLuminance(ph.powerIndex.rgb);
        farthest = max(farthest, nearestD2[base + uint(j)]);
    }
    radius = max(sqrt(farthest), treeMinRadius);
    return s;
}

#endif
