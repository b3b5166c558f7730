#version 450 core
// "gather" (pixel targets) and "bounce-gather" (GATHER_AT_POINTS): importance-driven point projection
// (Maletz, Wang & Bowers 2011, §3.2 and §4 "Microbuffers"), one work group per shading pixel:
//   1. exploration: N_rnd random points of every cluster (the 512 clusters are runs of the cloud's
//      median-split order, core/point_order.h), their summed importance p_k (Eq. 4: Eq. 1 times the
//      shading point's BRDF towards the point); they are projected at once, each representing 1 / N_rnd of
//      its cluster ("the splat size for a random point ... with p_k equal to the inverse of the number of
//      clusters");
//   2. allocation: the carry rule (§3.2's pseudo code) gives each cluster n_k of exactly N_s samples; all
//      p_k zero (every random point behind the tangent plane): uniform;
//   3. exploitation: N_s points drawn, n_k from cluster k, each splatted as a square of
//      sqrt(Omega_s / Omega_texel) texels with Omega_s by Eq. 5 (the robust Eq. 3) over the area
//      |C_k| dA / (N_s p_k) it stands for, clamped to half the buffer (a tiny p_k: huge splats);
//   4. resolve: the 32 x 32 hemi-octahedral micro-buffer (Eq. 2) keeps the nearest point per texel by a
//      32-bit (depth, point) key with atomicMin in shared memory (the paper's 64-bit colour + depth words
//      do not exist here); each texel's radiance times f_r cos Omega_texel, summed.
// A point facing away from the shading point is projected (it casts indirect shadows, §3.2) but
// reflects nothing towards it (one-sided surfaces). GLOSSY_POINTS: a point sends its glossy lobe's direct
// light too, evaluated towards the shading point (point_cloud.glsl's pointGlossyRadiance). PROJ_MODE 1
// draws uniformly (every p_k equal: Fig. 9's "random projection"), 2 projects every point with its own
// area (the brute-force reference of Fig. 9).
// SPLAT_FIXED n > 0: every splat n x n texels (Fig. 7's non-adaptive splats).
#include "common/bindings.glsl"
#define POINT_SURFELS
#define POINT_RADIANCE
#define POINT_GLOSSY
#ifdef HOLE_RAYS
#define SCENE_GEOMETRY
#endif
#include "common/random.glsl"
#include "frame/points/gather_target.glsl"
#include "technique/pointproj/bindings.glsl"
#include "technique/pointproj/projection.glsl"
#ifdef HOLE_RAYS
#include "common/raycast.glsl"
#include "frame/points/point_light.glsl"
#include "frame/points/hit_radiance.glsl" // after common/scene.glsl (point_light.glsl)
#endif

layout(local_size_x = PROJ_GROUP) in;
layout(std430, binding = SSBO_PROJ_TEXEL_SOLID_ANGLES) readonly buffer TexelSolidAngles { float texelSolidAngles[]; };
// 0 targets, 1 points projected, 2 texels left empty, 3 targets whose p_k were all zero, 4 splats clamped,
// 5 texels the hole fill covered, 6 rays cast through holes (HOLE_RAYS), 7 of them that hit a surface
layout(std430, binding = SSBO_PROJ_STATS) buffer ProjStats { uint projStats[8]; };

uniform uint pointCount;
uniform uint clusterSize;   // pointCount / CLUSTERS
uniform float depthScale;   // key depth = distance x depthScale
uniform float gatherOffset; // the shading point lifted off its surface (m)
uniform uint frameSeed;     // progressive mode: new random points every frame

const int kTexels = PROJ_RES * PROJ_RES;
const uint kEmptyKey = 0xFFFFFFFFu;
const uint kIndexMask = (1u << KEY_INDEX_BITS) - 1u;
const float kDepthMax = float((1u << (32 - KEY_INDEX_BITS)) - 2u);
const int kMaxSplat = PROJ_RES / 2;

shared uint projKeys[kTexels];
shared float clusterImportance[CLUSTERS];
shared uint clusterStart[CLUSTERS + 1]; // prefix sums of the counts n_k
shared float importanceTotal;
shared vec3 partDiffuse[PROJ_GROUP];
shared vec3 partGlossy[PROJ_GROUP];
shared uint groupStats[8];
#ifdef HOLE_RAYS
#if PROJ_RES * PROJ_RES > 32 * PROJ_GROUP
#error "an invocation's empty texels are bits of one uint"
#endif
shared uint holes[kTexels]; // 4b: the texels the splats and the fill left empty, by invocation, then texel
shared uint holeStart[PROJ_GROUP + 1];
#endif

// The r-th of n draws from a cluster: uniform in the r-th of n equal runs of its points. A cluster is a run
// of the median-split order, so its sub-runs are compact patches: n draws spread over the cluster's surface
// instead of falling on each other and leaving gaps (every point still equally likely).
uint stratifiedDraw(uint r, uint n, float u)
{
    float t = (float(r) + u) / float(max(n, 1u));
    return min(uint(t * float(clusterSize)), clusterSize - 1u);
}

// Eq. 3's area for a point drawn as `share` of its cluster's draws: the cluster's area |C_k| (its points' count
// times this point's area) times the share, but never less than the point's own disc. A near cluster drawn
// more often than it has points gets each point several times, and at the bare share every copy would
// be splatted a fraction of the point's size, at the same place: the rest of the cluster's solid angle
// stayed empty (whole octants of the micro-buffer next to a wall).
float shareArea(float pointArea, float share)
{
    return pointArea * max(float(clusterSize) * share, 1.0);
}

vec3 gx = vec3(0.0), gn = vec3(0.0, 0.0, 1.0), gt = vec3(1.0, 0.0, 0.0), gb = vec3(0.0, 1.0, 0.0); // the shading point (lifted), its frame

// Projects point j standing for `area` m^2 into the micro-buffer (Eq. 2, Eq. 5).
void splat(uint j, float area)
{
    PointSurfel s = pointSurfels[j];
    vec3 v = s.position - gx;
    float d2 = dot(v, v);
    if (!(d2 > 0.0)) return;
    float d = sqrt(d2);
    vec3 wl = vec3(dot(v, gt), dot(v, gb), dot(v, gn)) / d;
    if (wl.z <= 0.0) return; // behind the tangent plane: outside the hemisphere
    vec2 f = hemiOctEncode(wl) * float(PROJ_RES);
    ivec2 c = clamp(ivec2(f), ivec2(0), ivec2(PROJ_RES - 1));
#if SPLAT_FIXED > 0
    int side = SPLAT_FIXED;
#else
    float omega = robustSolidAngle(min(area, 1e30), dot(s.normal, v) / d, d2);
    float texels = omega / texelSolidAngles[c.y * PROJ_RES + c.x];
    int side = int(sqrt(max(texels, 1.0)) + 0.5); // the nearest square of Omega_s / Omega_texel texels
    if (side > kMaxSplat) {
        side = kMaxSplat;
        atomicAdd(groupStats[4], 1u);
    }
#endif
    uint key = (uint(min(d * depthScale, kDepthMax)) << KEY_INDEX_BITS) | j;
    // The side x side texels whose centres lie nearest the point's projection f: an odd side centred on its
    // texel, an even one leaning towards the side of the texel that f lies on. The point's own texel c is
    // always among them (f on the buffer's far edge is clamped into it).
    ivec2 first = clamp(ivec2(floor(f - 0.5 * float(side - 1))), c - (side - 1), c);
    ivec2 lo = max(first, ivec2(0));
    ivec2 hi = min(first + side - 1, ivec2(PROJ_RES - 1));
    for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) atomicMin(projKeys[y * PROJ_RES + x], key);
    atomicAdd(groupStats[1], 1u);
}

void main()
{
    uint k = gatherTargetIndex();
    if (k >= gatherTargetCount()) return; // the whole group
    GatherSample g = loadGatherSample(k);
    gn = g.normal;
    gt = abs(gn.x) < 0.9 ? normalize(cross(gn, vec3(1, 0, 0))) : normalize(cross(gn, vec3(0, 1, 0)));
    gb = cross(gn, gt);
    gx = g.position + gn * gatherOffset;
    float cosO = dot(gn, g.wo);
    uint lid = gl_LocalInvocationIndex;
    for (int p = int(lid); p < kTexels; p += PROJ_GROUP) projKeys[p] = kEmptyKey;
    if (lid < 8u) groupStats[lid] = 0u;
    barrier();
    uint seed = hashU(gatherTargetKey(g) ^ frameSeed * 2654435761u);

    if (cosO > 0.0) {
#if PROJ_MODE == 2
        for (uint j = lid; j < pointCount; j += uint(PROJ_GROUP)) splat(j, pointSurfels[j].areaM2);
#else
        // 1. Exploration: N_rnd random points per cluster, Eq. 4. SPLAT_SHARE_DRAWN: they are projected after
        // the allocation, sized for their share of all the points drawn from their cluster; else at once.
        for (uint c = lid; c < uint(CLUSTERS); c += uint(PROJ_GROUP)) {
            uint state = hashU(seed ^ (c * 0x85ebca6bu));
            float importance = 0.0;
            for (int r = 0; r < RANDOM_PER_CLUSTER; ++r) {
                uint j = c * clusterSize + stratifiedDraw(uint(r), uint(RANDOM_PER_CLUSTER), random01(state));
                PointSurfel s = pointSurfels[j];
                vec3 v = s.position - gx;
                float d2 = dot(v, v);
                float d = sqrt(max(d2, 1e-30));
                float f = dot(brdfEval(g.brdf, gn, g.wo, v / d), vec3(0.2126, 0.7152, 0.0722));
                importance += pointImportance(dot(gn, v) / d, dot(s.normal, v) / d, d2, s.areaM2) * f;
#if !SPLAT_SHARE_DRAWN
                splat(j, shareArea(s.areaM2, 1.0 / float(RANDOM_PER_CLUSTER)));
#endif
            }
#if PROJ_MODE == 1
            importance = 1.0;
#endif
            clusterImportance[c] = importance;
        }
        barrier();
        // 2. The carry rule, in one invocation (§4: "thread 0 goes through the PDF and assigns the number of
        // importance samples to each cluster"); every count and the start of every cluster's samples.
        if (lid == 0u) {
            float total = 0.0;
            for (int c = 0; c < CLUSTERS; ++c) total += clusterImportance[c];
            bool uniformPdf = !(total > 0.0) || isinf(total);
            if (uniformPdf) groupStats[3] = 1u;
            importanceTotal = uniformPdf ? 0.0 : total;
            uint state = hashU(seed ^ 0x27d4eb2fu);
            float carry = 0.0;
            uint assigned = 0u;
            for (int c = 0; c < CLUSTERS; ++c) {
                clusterStart[c] = assigned;
                float p = uniformPdf ? 1.0 / float(CLUSTERS) : clusterImportance[c] / total;
                uint n;
                if (c == CLUSTERS - 1) {
                    n = uint(SAMPLES) - assigned; // the float rounding of the carry: exactly N_s in all
                } else {
                    float fk = float(SAMPLES) * p + carry;
                    n = uint(max(fk, 0.0));
                    fk -= float(n);
                    if (random01(state) < fk) {
                        ++n;
                        carry = fk - 1.0;
                    } else {
                        carry = fk;
                    }
                    n = min(n, uint(SAMPLES) - assigned);
                }
                assigned += n;
            }
            clusterStart[CLUSTERS] = assigned;
        }
        barrier();
#if SPLAT_SHARE_DRAWN
        // The random points again (the same draws), each standing for 1 / (N_rnd + n_k) of its cluster.
        for (uint c = lid; c < uint(CLUSTERS); c += uint(PROJ_GROUP)) {
            uint state = hashU(seed ^ (c * 0x85ebca6bu));
            float share = 1.0 / float(RANDOM_PER_CLUSTER + int(clusterStart[c + 1u] - clusterStart[c]));
            for (int r = 0; r < RANDOM_PER_CLUSTER; ++r) {
                uint j = c * clusterSize + stratifiedDraw(uint(r), uint(RANDOM_PER_CLUSTER), random01(state));
                splat(j, shareArea(pointSurfels[j].areaM2, share));
            }
        }
#endif
        // 3. Exploitation: sample i belongs to the cluster whose run of counts holds it.
        float total = importanceTotal;
        for (uint i = lid; i < uint(SAMPLES); i += uint(PROJ_GROUP)) {
            int lo = 0, hi = CLUSTERS;
            while (hi - lo > 1) {
                int mid = (lo + hi) / 2;
                if (clusterStart[mid] <= i)
                    lo = mid;
                else
                    hi = mid;
            }
            uint state = hashU(seed ^ (i * 0xc2b2ae35u) ^ 0x165667b1u);
            uint n = clusterStart[lo + 1] - clusterStart[lo];
            uint j = uint(lo) * clusterSize + stratifiedDraw(i - clusterStart[lo], n, random01(state));
#if SPLAT_SHARE_DRAWN
            // The cluster's area shared by the N_rnd + n_k points drawn from it.
            float share = 1.0 / float(RANDOM_PER_CLUSTER + int(n));
#else
            // Eq. 3's area: the cluster's, shared by the N_s p_k samples expected from it.
            float p = total > 0.0 ? clusterImportance[lo] / total : 1.0 / float(CLUSTERS);
            float share = 1.0 / max(float(SAMPLES) * p, 1e-30);
#endif
            splat(j, shareArea(pointSurfels[j].areaM2, share));
        }
#endif
    }
    barrier();

#if HOLE_FILL > 0
    // 3b. Holes (not in the paper; gl/technique/pointproj/README.md): an empty texel more than half of whose
    // neighbours are covered takes the key of the farthest of them, HOLE_FILL times over. A gap between
    // splats closes from its rim inwards; the straight edge of an open direction (3 of 8 neighbours covered)
    // does not move. The farthest, because a gap at a silhouette is most often the far surface's: its splats
    // are the small ones.
    for (int pass = 0; pass < HOLE_FILL; ++pass) {
        uint fill[(kTexels + PROJ_GROUP - 1) / PROJ_GROUP];
        for (int p = int(lid), n = 0; p < kTexels; p += PROJ_GROUP, ++n) {
            fill[n] = kEmptyKey;
            if (projKeys[p] != kEmptyKey) continue;
            ivec2 t = ivec2(p % PROJ_RES, p / PROJ_RES);
            uint farthest = 0u;
            int neighbours = 0, covered = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    ivec2 q = t + ivec2(dx, dy);
                    if ((dx == 0 && dy == 0) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(PROJ_RES))))
                        continue;
                    ++neighbours;
                    uint key = projKeys[q.y * PROJ_RES + q.x];
                    if (key == kEmptyKey) continue;
                    ++covered;
                    farthest = max(farthest, key);
                }
            if (2 * covered > neighbours) fill[n] = farthest;
        }
        barrier();
        uint filled = 0u;
        for (int p = int(lid), n = 0; p < kTexels; p += PROJ_GROUP, ++n)
            if (fill[n] != kEmptyKey) {
                projKeys[p] = fill[n];
                ++filled;
            }
        if (filled > 0u) atomicAdd(groupStats[5], filled);
        barrier();
    }
#endif

    // 4. Resolve: each texel's nearest point, its radiance times f_r cos Omega_texel.
    vec3 sumDiffuse = vec3(0.0), sumGlossy = vec3(0.0);
    uint empty = 0u, holeMask = 0u; // holeMask bit n: this invocation's n-th texel is empty
    for (int p = int(lid); p < kTexels && cosO > 0.0; p += PROJ_GROUP) {
        vec3 wl = hemiOctDecode((vec2(p % PROJ_RES, p / PROJ_RES) + 0.5) / float(PROJ_RES));
        uint key = projKeys[p];
        if (key == kEmptyKey) {
#ifdef HOLE_RAYS
            holeMask |= 1u << uint((p - int(lid)) / PROJ_GROUP);
#else
            ++empty;
#endif
            continue;
        }
        uint j = key & kIndexMask;
        PointSurfel s = pointSurfels[j];
        if (dot(s.normal, gx - s.position) <= 0.0) continue; // its back: black
        vec3 radiance = unpackRadiance(pointRadiance[j]);
#ifdef GLOSSY_POINTS
        radiance += pointGlossyRadiance(pointGlossy[j], s.normal, normalize(gx - s.position));
#endif
        vec3 wi = gt * wl.x + gb * wl.y + gn * wl.z;
        gatherAdd(g, wi, radiance, wl.z * texelSolidAngles[p], sumDiffuse, sumGlossy);
    }
#ifdef HOLE_RAYS
    // 4b. Holes (not in the paper; gl/technique/pointproj/README.md): a texel no splat covered casts a ray
    // through its centre, listed first so that every invocation casts. Where the ray meets the scene the
    // texel sees a surface that the drawn points missed: the hit's direct light, as a point there would send
    // it (hit_radiance.glsl); where it meets nothing the direction is open and stays empty, so that a hole
    // is never filled into open space. The list is in a fixed order (each invocation's holes from its place
    // in a scan of their counts), so that every run sums the same rays in the same invocations.
    holeStart[lid + 1u] = uint(bitCount(holeMask));
    barrier();
    if (lid == 0u) {
        holeStart[0] = 0u;
        for (int i = 1; i <= PROJ_GROUP; ++i) holeStart[i] += holeStart[i - 1];
    }
    barrier();
    for (uint n = 0u, at = holeStart[lid]; n < uint((kTexels + PROJ_GROUP - 1) / PROJ_GROUP); ++n)
        if ((holeMask & (1u << n)) != 0u) holes[at++] = lid + n * uint(PROJ_GROUP);
    barrier();
    uint rays = 0u, hits = 0u, holeCount = holeStart[PROJ_GROUP];
    for (uint i = lid; i < holeCount; i += uint(PROJ_GROUP)) {
        int p = int(holes[i]);
        vec3 wl = hemiOctDecode((vec2(p % PROJ_RES, p / PROJ_RES) + 0.5) / float(PROJ_RES));
        vec3 wi = gt * wl.x + gb * wl.y + gn * wl.z;
        ++rays;
        Hit hit;
        if (!closestHit(gx, wi, 0.0, 1e30, hit)) {
            ++empty;
            continue;
        }
        ++hits;
        vec3 hn = sceneTriangleNormal(hit.triangle, hit.b);
        if (dot(hn, wi) >= 0.0) continue; // its back: black
        vec3 radiance = hitDirectRadiance(hit.triangle, hit.b, gx + wi * hit.t, hn, -wi);
        gatherAdd(g, wi, radiance, wl.z * texelSolidAngles[p], sumDiffuse, sumGlossy);
    }
    atomicAdd(groupStats[6], rays);
    atomicAdd(groupStats[7], hits);
#endif
    partDiffuse[lid] = sumDiffuse;
    partGlossy[lid] = sumGlossy;
    atomicAdd(groupStats[2], empty);
    barrier();
    if (lid == 0u) {
        vec3 d = vec3(0.0), s = vec3(0.0);
        for (int i = 0; i < PROJ_GROUP; ++i) {
            d += partDiffuse[i];
            s += partGlossy[i];
        }
        storeGather(g, k, d, s);
        atomicAdd(projStats[0], 1u);
        for (int i = 1; i < 8; ++i) atomicAdd(projStats[i], groupStats[i]);
    }
}
