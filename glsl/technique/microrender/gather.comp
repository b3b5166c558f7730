#version 450 core
// "gather" (pixel targets) and "bounce-gather" (GATHER_AT_POINTS): micro-rendering (Ritschel et al. 2009),
// one work group per gather sample, the §3.2 single kernel: "each thread first computes the BRDF warping
// functions, and then continues to compute the point hierarchy cut ... The output of this first step is a
// partially finished micro-buffer and the post-traversal list. ... The threads with a non-empty list cast
// one ray for every micro-pixel ... After filling the micro-buffers, each thread computes the reflected
// radiance by summing up its content." Here the group's MICRO_GROUP invocations share one sample:
//   1. warp: the mixture of the BRDF's lobe tables and its CDFs in shared memory (warp.glsl, §2.3);
//   2. cut: each invocation walks one subtree under hierarchy level log2(MICRO_GROUP) depth first without a
//      stack (heap indices give the skip pointers, §2.1), descending while the node's solid angle exceeds the
//      micro-pixel's at its direction (§2.2, "Point Hierarchy Cut"; a leaf: its disc, A cos / d^2; an
//      interior node: what its surfels can subtend, min(its sphere's, A / d^2)), and rasterises the others into the
//      shared micro-buffer: depth and node index in one 32-bit key, atomicMin (§3.1: 8 + 24 bits there);
//      back-facing nodes (normal cones) and nodes under the horizon are culled;
//   3. rays (RAY_CAST, §2.2 "On-demand Ray Casting"): leaves still larger than a micro-pixel go to the
//      post-traversal list instead; when it is not empty, one ray per micro-pixel through the frame's GPU
//      ray casting (common/raycast.glsl); a hit nearer than the pixel's node takes the pixel, with the
//      radiance of the listed leaf whose disc holds the hit, else the lights' at the hit (GLOSSY_POINTS:
//      every lobe of the hit's BRDF towards the sample); departure: rays also where the micro-pixel's
//      point rasterisation is unsure (below, "Silhouettes");
//   4. convolution: each micro-pixel's radiance times f cos Omega at its direction (Omega from the warp's
//      Jacobian), summed: with the warp proportional to f this is rho times the mean of the micro-pixels.
// Silhouettes (departure; SILHOUETTE_RAYS, with RAY_CAST): a micro-pixel takes the nearest node whose
// centre falls in it, however little of it the node covers, so every silhouette is dilated by up to a
// micro-pixel: against the void (the Cornell box's open front) or a darker surface behind, that adds light
// (+7.6% on cornell-spot's one bounce at 24 x 24). Each rasterised node therefore also adds its share of the
// micro-pixel's solid angle (at most 1, an interior node's projected by the most its normal cone can face
// the sample) and raises the pixel's farthest depth. A pixel the shares do not fill, or (SILHOUETTE_DEPTHS)
// whose nodes lie at depths farther apart than the nearest node's sphere, holds a silhouette: a ray through
// its jittered direction decides it, as the path tracer does (a miss: the void; a hit farther than the
// nearest node: the surface behind; near it: the node). The pixels the surfaces fill keep the paper's
// rasterisation.
// GLOSSY_POINTS: a node sends its glossy lobe's direct light too, evaluated towards the sample
// (hierarchy.glsl's nodeRadiance), so that light -> glossy -> receiver paths are gathered.
// Results: the diffuse part without the receiver's diffuse colour and the glossy part (gather_target.glsl).
// Defines: MICRO_RES (8, 16, 24), MICRO_GROUP (64), WARP_BINS, KEY_INDEX_BITS, LIST_CAP, RAY_CAST,
// SILHOUETTE_RAYS (with RAY_CAST and without RAY_DISCS), SILHOUETTE_DEPTHS (with SILHOUETTE_RAYS),
// GATHER_AT_POINTS, PUNCTUAL_LIGHTS / AREA_LIGHTS (the lights at ray hits), MICRO_STAGES (4; fewer runs
// only the first stages, for the time split by stage of §5: 1 the warp, 2 + the cut, 3 + the rays),
// CUT_QUEUE (the cut's walk by levels, below).
//
// The cut's two walks (MicroGatherSettings::cutByLevels) rasterise the same nodes, and atomicMin keeps the
// nearest key whatever the order: the same micro-buffer. The walk by subtrees above is the paper's one
// thread per walk, but its 64 subtrees differ in size by orders of magnitude (the surfaces near the sample
// are refined to their leaves, those behind it culled at once), so a group waits for its longest walk. The
// walk by levels (CUT_QUEUE: the capacity of each of two queues) shares the work instead: the group takes
// the nodes of one level from a queue in shared memory, 64 at a time, and queues the children of the nodes
// it refines for the next round; children that find a queue full are walked by their parent's invocation
// as a subtree. One round and two barriers per level of the hierarchy: for a GPU, where the warps of a
// group run in lockstep; the subtrees suit a CPU rasteriser, whose barriers are costly.
#define SCENE_GEOMETRY
#include "common/random.glsl"
#include "frame/points/gather_target.glsl"
#include "technique/microrender/hierarchy.glsl"
#include "technique/microrender/warp.glsl"
#ifdef RAY_CAST
#include "common/raycast.glsl"
#include "frame/points/point_light.glsl"
#include "frame/points/hit_radiance.glsl" // after common/scene.glsl (point_light.glsl)
#endif

layout(local_size_x = MICRO_GROUP) in;
layout(std430, binding = SSBO_MICRO_NODES) readonly buffer MicroNodes { MicroNode microNodes[]; };
// 0 samples, 1 samples with a post-traversal list, 2 lists that overflowed, 3 micro-pixels left empty,
// 4 nodes visited, 5 nodes rasterised, 6 rays cast, 7 micro-pixels taken by a ray
layout(std430, binding = SSBO_MICRO_STATS) buffer MicroStats { uint microStats[8]; };

uniform uint leafCount;
uniform float depthScale;   // key depth = distance x depthScale, KEY_DEPTH_MAX at most
uniform float cutScale;

const uint kEmptyKey = 0xFFFFFFFFu;
const uint kRayKey = 0xFFFFFFFEu;
const uint kIndexMask = (1u << KEY_INDEX_BITS) - 1u;
const float kDepthMax = float((1u << (32 - KEY_INDEX_BITS)) - 2u);
const int kPixels = MICRO_RES * MICRO_RES;

shared uint microKeys[kPixels];
shared vec3 partDiffuse[MICRO_GROUP];
shared vec3 partGlossy[MICRO_GROUP];
shared uint groupStats[8];
// The radiance of the micro-pixels a ray took (three words each, RAY_CAST), and before the rays the walk's
// two queues (CUT_QUEUE): one array for both, so that the queues cost no shared memory at 24 x 24.
#if defined(CUT_QUEUE) && defined(RAY_CAST)
const int kScratch = max(3 * kPixels, 2 * CUT_QUEUE);
#elif defined(CUT_QUEUE)
const int kScratch = 2 * CUT_QUEUE;
#elif defined(RAY_CAST)
const int kScratch = 3 * kPixels;
#endif
#if defined(CUT_QUEUE) || defined(RAY_CAST)
shared uint scratch[kScratch];
#endif
#ifdef CUT_QUEUE
shared uint queueCount[2];
#endif
#ifdef RAY_CAST
shared uint listNodes[LIST_CAP];
shared uint listCount;
#endif
#ifdef SILHOUETTE_RAYS
// Per micro-pixel, the rasterised nodes' summed shares of its solid angle (kCoverFull: all of it) and their
// farthest depth (the keys' units): "Silhouettes" above.
shared uint microCover[kPixels];
shared uint microFar[kPixels];
const uint kCoverFull = 1024u;
#endif

#ifdef RAY_CAST
// Micro-pixel p taken by a ray (either kind of ray below), with the radiance the ray brings back: three
// words of the scratch array, which the convolution reads (rayRadiance).
void takeByRay(int p, vec3 radiance)
{
    scratch[3 * p] = floatBitsToUint(radiance.r);
    scratch[3 * p + 1] = floatBitsToUint(radiance.g);
    scratch[3 * p + 2] = floatBitsToUint(radiance.b);
    microKeys[p] = kRayKey;
}
vec3 rayRadiance(int p) { return uintBitsToFloat(uvec3(scratch[3 * p], scratch[3 * p + 1], scratch[3 * p + 2])); }
#endif

// A node faces away from x when no normal of its cone can see x from any point of its sphere: the angle
// between the cone axis and the direction to x exceeds 90 degrees + the cone's half angle + the sphere's
// angular radius seen from x.
bool backFacing(vec4 cone, vec3 v, float d2, float r)
{
    if (cone.w >= kConeAll || d2 <= r * r) return false;
    float d = sqrt(d2);
    float alpha = acos(clamp(dot(cone.xyz, -v) / d, -1.0, 1.0));
    return alpha > 0.5 * kConeAll + cone.w + asin(r / d);
}

// The sample as the cut sees it: its lifted position and its frame.
struct CutFrame {
    vec3 x, n, tangent, bitangent;
};
uint visitedNodes = 0u, rasterisedNodes = 0u; // this invocation's

// One node of the cut: culled (back-facing, under the horizon), rasterised into the micro-buffer, listed
// for rays, or refined: returns true when its children are to be visited.
bool cutVisit(CutFrame f, uint node)
{
    MicroNode nd = microNodes[node];
    vec3 v = nd.sphere.xyz - f.x;
    float r = nd.sphere.w, d2 = dot(v, v), h = dot(v, f.n);
    bool isLeaf = node >= leafCount;
    bool descend = false;
    ++visitedNodes;
    if (h > -r && !backFacing(nd.cone, v, d2, r) && !(isLeaf && h <= 0.0)) {
        float d = sqrt(d2);
        // A node straddling the horizon is judged at the top of its sphere, the part that can be seen.
        vec3 top = h >= 0.0 ? v : v + f.n * r;
        vec3 wl = normalize(vec3(dot(top, f.tangent), dot(top, f.bitangent), dot(top, f.n)));
        float omega;
        if (isLeaf)
            omega = nd.areaM2 * abs(dot(nd.cone.xyz, v)) / max(d2 * d, 1e-30); // the disc's solid angle
        else if (d2 <= r * r)
            omega = 1e30; // inside its sphere: always descend
        else // what its surfels subtend: at most their area over d^2, at most the sphere's solid angle
            omega = min(2.0 * kConeAll * (1.0 - sqrt(1.0 - r * r / d2)), nd.areaM2 / d2);
        bool large = omega > cutScale * warpPixelSolidAngle(wl);
#ifdef GLOSSY_POINTS
        // An interior node sends its glossy lobe about its cone's axis: only a node whose normals stay within
        // the lobe's width (its roughness, sqrt(alpha), in radians) may stand for its points' lobes.
        large = large || (!isLeaf && glossyTooWide(nd));
#endif
        if (large && !isLeaf) {
            descend = true;
        } else if (h >= 0.0) {
#ifdef RAY_CAST
            if (large) {
                uint slot = atomicAdd(listCount, 1u);
                if (slot < uint(LIST_CAP)) listNodes[slot] = node;
            } else
#endif
            {
                ivec2 c = warpCellOf(warpToUnit(wl));
                uint q = uint(min(d * depthScale, kDepthMax));
                atomicMin(microKeys[c.y * MICRO_RES + c.x], (q << KEY_INDEX_BITS) | node);
#ifdef SILHOUETTE_RAYS
                float share = omega / warpPixelSolidAngle(wl);
                if (!isLeaf && nd.cone.w < kConeAll) { // A / d^2 projected by the cone's most facing normal
                    float tilt = acos(min(abs(dot(nd.cone.xyz, v)) / d, 1.0));
                    share *= cos(min(max(tilt - nd.cone.w, 0.0), 0.5 * kPi));
                }
                atomicAdd(microCover[c.y * MICRO_RES + c.x], uint(min(share, 1.0) * float(kCoverFull)));
                atomicMax(microFar[c.y * MICRO_RES + c.x], q);
#endif
                ++rasterisedNodes;
            }
        }
    }
    return descend;
}

// The subtree under `start`, depth first without a stack: heap indices give the skip pointers.
void cutWalk(CutFrame f, uint start)
{
    uint node = start;
    while (true) {
        if (cutVisit(f, node)) {
            node = 2u * node;
            continue;
        }
        while (node != start && (node & 1u) == 1u) node >>= 1u;
        if (node == start) break;
        node += 1u;
    }
}

#ifdef CUT_QUEUE
// The whole cut by levels, from the MICRO_GROUP nodes of level log2(MICRO_GROUP), shared by the group
// (in uniform control flow: every invocation reads the same counts after each barrier).
void cutByLevels(CutFrame f, uint lid)
{
    scratch[lid] = uint(MICRO_GROUP) + lid;
    if (lid == 0u) {
        queueCount[0] = uint(MICRO_GROUP);
        queueCount[1] = 0u;
    }
    barrier();
    uint current = 0u;
    for (;;) {
        uint count = min(queueCount[current], uint(CUT_QUEUE));
        if (count == 0u) break;
        uint next = 1u - current;
        for (uint i = lid; i < count; i += uint(MICRO_GROUP)) {
            uint node = scratch[current * uint(CUT_QUEUE) + i];
            if (!cutVisit(f, node)) continue;
            uint slot = atomicAdd(queueCount[next], 2u); // even, as CUT_QUEUE: a pair fits or none
            if (slot < uint(CUT_QUEUE)) {
                scratch[next * uint(CUT_QUEUE) + slot] = 2u * node;
                scratch[next * uint(CUT_QUEUE) + slot + 1u] = 2u * node + 1u;
            } else {
                cutWalk(f, 2u * node);
                cutWalk(f, 2u * node + 1u);
            }
        }
        barrier(); // every push done, every read of this round's count done
        if (lid == 0u) queueCount[current] = 0u;
        current = next;
        barrier();
    }
}
#endif

void main()
{
    uint k = gatherTargetIndex();
    if (k >= gatherTargetCount()) return; // the whole group: one target per group
    uint lid = gl_LocalInvocationIndex;
    GatherSample g = loadGatherSample(k);
    vec3 n = g.normal;
    // The local frame: the view direction's tangent part on +x, where the GGX tables put it.
    vec3 tangent = g.wo - n * dot(n, g.wo);
    if (dot(tangent, tangent) < 1e-8) tangent = abs(n.x) < 0.9 ? cross(n, vec3(1, 0, 0)) : cross(n, vec3(0, 1, 0));
    tangent = normalize(tangent);
    vec3 bitangent = cross(n, tangent);
    float cosO = dot(n, g.wo);
    float share = warpSpecularShare(g.brdf, cosO);
#ifdef NO_WARP
    share = 0.0; // the Nusselt (cosine) mapping for every BRDF, weighted by f at the convolution
#endif
    warpBuild(share, share > 0.0 ? warpGgxTable(cosO, g.brdf.alpha) : 0, lid);
    // §2.3: "we jitter the local coordinate system slightly at every gather sample to avoid banding": each
    // micro-pixel's direction is taken at a point of it jittered per target, and a frame without a glossy
    // lobe to align with is turned about the normal by a random angle. Seeded by the target's texel (or
    // point), so that the image is the same in every run.
    uint seed = hashU(gatherTargetKey(g));
    vec2 jitter = (vec2(float(seed & 0xFFFFu), float(seed >> 16)) + 0.5) / 65536.0 - 0.5;
    if (share == 0.0) {
        float turn = 2.0 * kPi * float(hashU(seed) & 0xFFFFu) / 65536.0;
        vec3 t2 = cos(turn) * tangent + sin(turn) * bitangent;
        bitangent = cross(n, t2);
        tangent = t2;
    }
    for (int p = int(lid); p < kPixels; p += MICRO_GROUP) microKeys[p] = kEmptyKey;
#ifdef SILHOUETTE_RAYS
    for (int p = int(lid); p < kPixels; p += MICRO_GROUP) { microCover[p] = 0u; microFar[p] = 0u; }
#endif
    if (lid < 8u) groupStats[lid] = 0u;
#ifdef RAY_CAST
    if (lid == 0u) listCount = 0u;
#endif
    barrier();

    // The gather point lifted off its surface by a ray's offset (common/scene.glsl): its own surface's points lie
    // under its horizon and its rays leave its triangle. Half a point's disc radius (7 cm on Sponza at 65,536
    // points) lifted it over the floor's and the walls' nearest shade: the indirect light on a white
    // Lambertian copy of assets/setups/sponza-sun.json read 1.047 of the path tracer's, 1.011 now (README).
    vec3 x = g.position + n * surfaceRayOffset(g.position);
    CutFrame f = CutFrame(x, n, tangent, bitangent);
    if (cosO > 0.0 && MICRO_STAGES >= 2) {
#ifdef CUT_QUEUE
        cutByLevels(f, lid);
#else
        cutWalk(f, uint(MICRO_GROUP) + lid);
#endif
    }
    atomicAdd(groupStats[4], visitedNodes);
    atomicAdd(groupStats[5], rasterisedNodes);
    barrier();

#ifdef RAY_CAST
    // Rays through every micro-pixel when the list holds something (the paper), and through every pixel
    // the cut left empty (a hole between nodes: the closed-scene guarantee). The list's order, and which
    // nodes an overflowing list kept, follow the order in which invocations reached atomicAdd: a GPU runs
    // them in another order every time. So the search below takes the nearest node with ties to the lower
    // index, and an overflowed list is not read at all (every hit takes the direct light at the hit, as a
    // hit no listed leaf holds does): the same image in every run, on any driver.
    uint listed = listCount > uint(LIST_CAP) ? 0u : listCount;
    bool everyPixel = listCount > 0u;
    uint rays = 0u, taken = 0u;
#ifdef RAY_DISCS
    // The paper's rays (RAY_DISCS): when the list holds leaves, one ray per micro-pixel against the listed
    // leaves' discs only (centre, normal, r = sqrt(area / pi)), the nearest in front of the pixel's node
    // taking it with the leaf's radiance, ties to the lower index; no ray where the list is empty, so a
    // pixel the cut left empty stays empty (the paper's holes). An overflowed list takes the rays through
    // the triangles below.
    bool discs = listCount > 0u && listCount <= uint(LIST_CAP);
    for (int p = int(lid); p < kPixels && discs && cosO > 0.0 && MICRO_STAGES >= 3; p += MICRO_GROUP) {
        vec3 wl = warpToDirection(warpCellSample(ivec2(p % MICRO_RES, p / MICRO_RES), jitter));
        if (wl.z <= 0.0) continue;
        vec3 dir = tangent * wl.x + bitangent * wl.y + n * wl.z;
        uint key = microKeys[p];
        float nearest = key == kEmptyKey ? 1e30 : (float(key >> KEY_INDEX_BITS) + 1.0) / depthScale;
        uint best = 0u;
        ++rays;
        for (uint e = 0u; e < listed; ++e) {
            MicroNode ln = microNodes[listNodes[e]];
            float facing = dot(dir, ln.cone.xyz);
            if (facing >= 0.0) continue; // the disc's back: culled, as in the cut
            float t = dot(ln.sphere.xyz - x, ln.cone.xyz) / facing;
            vec3 off = x + dir * t - ln.sphere.xyz;
            bool nearer = t < nearest || (t == nearest && best != 0u && listNodes[e] < best);
            if (t > 0.0 && nearer && dot(off, off) <= ln.sphere.w * ln.sphere.w) {
                nearest = t;
                best = listNodes[e];
            }
        }
        if (best == 0u) continue;
        takeByRay(p, nodeRadiance(microNodes[best], -dir));
        ++taken;
    }
    bool triangles = listCount > uint(LIST_CAP);
#else
    const bool triangles = true;
#endif
    for (int p = int(lid); p < kPixels && triangles && cosO > 0.0 && MICRO_STAGES >= 3; p += MICRO_GROUP) {
        uint key = microKeys[p];
        float keyDepth = key == kEmptyKey ? 1e30 : (float(key >> KEY_INDEX_BITS) + 1.0) / depthScale;
#ifdef SILHOUETTE_RAYS
        float keyReach = key == kEmptyKey ? 0.0 : 2.0 * microNodes[key & kIndexMask].sphere.w;
        // A silhouette (see the top): the ray's answer stands, also a miss or a hit behind the node.
        bool partial = microCover[p] < kCoverFull;
#ifdef SILHOUETTE_DEPTHS
        partial = partial || float(microFar[p]) / depthScale > keyDepth + keyReach;
#endif
#else
        const float keyReach = 0.0;
        const bool partial = false;
#endif
        if (!everyPixel && !partial && key != kEmptyKey) continue;
        vec3 wl = warpToDirection(warpCellSample(ivec2(p % MICRO_RES, p / MICRO_RES), jitter));
        if (wl.z <= 0.0) continue;
        vec3 dir = tangent * wl.x + bitangent * wl.y + n * wl.z;
        ++rays;
        Hit hit;
        if (!closestHit(x, dir, 0.0, 1e30, hit)) {
            if (partial) microKeys[p] = kEmptyKey;
            continue;
        }
        if (hit.t >= keyDepth && (!partial || hit.t <= keyDepth + keyReach)) continue;
        vec3 hp = x + dir * hit.t;
        vec3 hn = sceneTriangleNormal(hit.triangle, hit.b);
        vec3 radiance = vec3(0.0);
        if (dot(hn, dir) < 0.0) { // the front of a one-sided surface (its back is black)
            uint best = 0u;
            float bestD2 = 1e30;
            for (uint e = 0u; e < listed; ++e) {
                MicroNode ln = microNodes[listNodes[e]];
                vec3 dd = hp - ln.sphere.xyz;
                float dist2 = dot(dd, dd), reach = 2.0 * ln.sphere.w;
                bool nearer = dist2 < bestD2 || (dist2 == bestD2 && listNodes[e] < best);
                if (nearer && dist2 <= reach * reach && dot(ln.cone.xyz, hn) > 0.5) {
                    bestD2 = dist2;
                    best = listNodes[e];
                }
            }
            if (best != 0u) {
                radiance = nodeRadiance(microNodes[best], -dir);
            } else {
                radiance = hitDirectRadiance(hit.triangle, hit.b, hp, hn, -dir);
            }
        }
        takeByRay(p, radiance);
        ++taken;
    }
    atomicAdd(groupStats[6], rays);
    atomicAdd(groupStats[7], taken);
    barrier();
#endif

    // Convolution: sum of L_in f cos Omega over the micro-pixels, the diffuse and glossy lobes apart.
    vec3 sumDiffuse = vec3(0.0), sumGlossy = vec3(0.0);
    uint empty = 0u;
    for (int p = int(lid); p < kPixels && cosO > 0.0 && MICRO_STAGES >= 4; p += MICRO_GROUP) {
        uint key = microKeys[p];
        vec3 wl = warpToDirection(warpCellSample(ivec2(p % MICRO_RES, p / MICRO_RES), jitter));
        if (key == kEmptyKey) {
            if (wl.z > 0.0) ++empty; // (a direction on the horizon weighs nothing, and no ray is cast along it)
            continue;
        }
#ifdef RAY_CAST
        vec3 wi = tangent * wl.x + bitangent * wl.y + n * wl.z;
        vec3 radiance = key == kRayKey ? rayRadiance(p) : nodeRadiance(microNodes[key & kIndexMask], -wi);
#else
        vec3 wi = tangent * wl.x + bitangent * wl.y + n * wl.z;
        vec3 radiance = nodeRadiance(microNodes[key & kIndexMask], -wi);
#endif
        gatherAdd(g, wi, radiance, warpCosineSolidAngle(wl), sumDiffuse, sumGlossy);
    }
    partDiffuse[lid] = sumDiffuse;
    partGlossy[lid] = sumGlossy;
    atomicAdd(groupStats[3], empty);
    barrier();
    if (lid == 0u) {
        vec3 d = vec3(0.0), s = vec3(0.0);
        for (int i = 0; i < MICRO_GROUP; ++i) { // in order: the same sum in every run
            d += partDiffuse[i];
            s += partGlossy[i];
        }
        storeGather(g, k, d, s);
        atomicAdd(microStats[0], 1u);
#ifdef RAY_CAST
        if (listCount > 0u) atomicAdd(microStats[1], 1u);
        if (listCount > uint(LIST_CAP)) atomicAdd(microStats[2], 1u);
#endif
        for (int i = 3; i < 8; ++i) atomicAdd(microStats[i], groupStats[i]);
    }
}
