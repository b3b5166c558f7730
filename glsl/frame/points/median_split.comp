#version 450 core
// The median-split order of core/point_order.h (every level, the longest axis) on the GPU
// (gl/frame/points/median_split.h): importance-driven point projection re-clusters the points when the
// scene is manipulated, "each level of split on the GPU using a segmented global sort" (Maletz, Wang &
// Bowers 2011, §4). Here the three lists of the points sorted by x, by y and by z are sorted once (the
// frame's radix sort, stable, so that equal coordinates keep the points' index order: core's tie rule),
// and each level is a stable partition of every segment of every list around its median: the sort by
// (segment, coordinate) that the paper runs per level, without sorting again what is sorted. A segment's
// extent along an axis is the first and last point of that axis's list, its median the middle of the
// longest axis's list. Stages (STAGE):
//   KEYS     positions -> keys[i] = the orderable bits of coordinate `axis` of point i, values[i] = i
//   SIDE     per position p of the longest axis's list of p's segment: side[point] = 0 below the median
//   FLAGS    per list k and position p: scan[k n + p] = 1 where the point goes to the lower half
//   SCATTER  per list k and position p: the point to its place in the partitioned segment (scan: the
//            exclusive prefix sums of FLAGS)
//   PERMUTE  samples in the final order (uvec4 each, PointSample's 16 bytes)
// A segment is a node of the level: [0, n) halved `level` times, the lower half floor(m / 2), a segment
// of fewer than two points not split again (core's rule, so that the two orders are the same).
#include "common/bindings.glsl"
#include "frame/points/bindings.glsl"
#include "frame/sort_bindings.glsl"
#define STAGE_KEYS 0
#define STAGE_SIDE 1
#define STAGE_FLAGS 2
#define STAGE_SCATTER 3
#define STAGE_PERMUTE 4
layout(local_size_x = 64) in;

// Each stage declares only the blocks it reads or writes (a declared block counts and must be bound).
#if STAGE == STAGE_KEYS || STAGE == STAGE_SIDE
layout(std430, binding = SSBO_MEDIAN_POSITIONS) readonly buffer Positions { float positions[]; };
#endif
#if STAGE == STAGE_KEYS
layout(std430, binding = SSBO_SORT_KEYS) writeonly buffer Keys { uint keys[]; };
layout(std430, binding = SSBO_SORT_VALUES) writeonly buffer Values { uint values[]; };
#else
layout(std430, binding = SSBO_MEDIAN_LISTS) readonly buffer Lists { uint lists[]; };
#endif
#if STAGE == STAGE_SCATTER
layout(std430, binding = SSBO_MEDIAN_LISTS_OUT) writeonly buffer ListsOut { uint listsOut[]; };
#endif
#if STAGE == STAGE_SIDE || STAGE == STAGE_FLAGS || STAGE == STAGE_SCATTER
layout(std430, binding = SSBO_MEDIAN_SIDE) buffer Side { uint side[]; };
#endif
#if STAGE == STAGE_FLAGS || STAGE == STAGE_SCATTER
layout(std430, binding = SSBO_SCAN) buffer Scan { uint scan[]; };
#endif
#if STAGE == STAGE_PERMUTE
layout(std430, binding = SSBO_POINT_SAMPLES) readonly buffer Samples { uvec4 samples[]; };
layout(std430, binding = SSBO_MEDIAN_SAMPLES_OUT) writeonly buffer SamplesOut { uvec4 samplesOut[]; };
#endif

uniform uint count;
uniform uint stride; // floats from one point's position to the next's
uniform uint axis;   // KEYS
uniform int level;   // SIDE, FLAGS, SCATTER

bool finiteBits(float x) { return (floatBitsToUint(x) & 0x7f800000u) != 0x7f800000u; }

#if STAGE == STAGE_KEYS || STAGE == STAGE_SIDE
// core's finiteOrZero: a point with a coordinate that is NaN or infinite lies at the origin.
float coordinate(uint point, uint a)
{
    uint i = point * stride;
    bool finite = finiteBits(positions[i]) && finiteBits(positions[i + 1u]) && finiteBits(positions[i + 2u]);
    return finite ? positions[i + a] : 0.0;
}
#endif

// The bits of a coordinate, ordered as unsigned integers as the floats are ordered, -0 as +0 (core compares
// floats: -0 == +0, ties by index). On the bits, so that no flush of denormals can change an order.
uint orderedBits(float x)
{
    uint b = floatBitsToUint(x);
    if ((b & 0x7fffffffu) == 0u) b = 0u;
    return (b & 0x80000000u) != 0u ? ~b : b | 0x80000000u;
}

// The segment of position p at `level`: [begin, end).
uvec2 segmentOf(uint p)
{
    uint begin = 0u, end = count;
    for (int l = 0; l < level && end - begin >= 2u; ++l) {
        uint mid = begin + (end - begin) / 2u;
        if (p < mid)
            end = mid;
        else
            begin = mid;
    }
    return uvec2(begin, end);
}

void main()
{
    uint p = gl_GlobalInvocationID.x;
    if (p >= count) return;
#if STAGE == STAGE_KEYS
    keys[p] = orderedBits(coordinate(p, axis));
    values[p] = p;
#elif STAGE == STAGE_PERMUTE
    samplesOut[p] = samples[lists[p]];
#else
    uvec2 s = segmentOf(p);
    bool split = s.y - s.x >= 2u;
    uint mid = s.x + (s.y - s.x) / 2u;
#if STAGE == STAGE_SIDE
    if (!split) return;
    // core's rule: the longest extent, x before y before z on ties.
    vec3 e;
    for (uint a = 0u; a < 3u; ++a)
        e[a] = coordinate(lists[a * count + s.y - 1u], a) - coordinate(lists[a * count + s.x], a);
    uint longest = (e.x >= e.y && e.x >= e.z) ? 0u : (e.y >= e.z ? 1u : 2u);
    side[lists[longest * count + p]] = p < mid ? 0u : 1u;
#else
    uint k = gl_GlobalInvocationID.y;
    uint point = lists[k * count + p];
#if STAGE == STAGE_FLAGS
    scan[k * count + p] = split && side[point] == 0u ? 1u : 0u;
#elif STAGE == STAGE_SCATTER
    uint slot = p;
    if (split) {
        uint below = scan[k * count + p] - scan[k * count + s.x]; // lower-half points before p in the segment
        slot = side[point] == 0u ? s.x + below : mid + (p - s.x - below);
    }
    listsOut[k * count + slot] = point;
#endif
#endif
#endif
}
