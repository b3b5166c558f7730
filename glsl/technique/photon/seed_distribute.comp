#version 450 core
// Adaptive seeding (section 3.2), one quadtree level, top-down: each node hands its seeds to its four
// children in proportion to their geometric variation eps_q (capped at their members; by members when no
// child varies), the integer parts first, then one more to the largest remainders; a node with one seed
// gives it to one child at random in proportion to its members (the paper's jittered sample within the
// quad). The root takes min(seedCount, members). Seed slots stay contiguous: a node's seeds are
// [first, first + count), its children's consecutive ranges of them.
#define CLUSTERS_UNUSED
#include "technique/photon/cluster_quadtree.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = SSBO_CLUSTER_SEEDS) buffer Seeds { uvec2 seeds[]; };
layout(std430, binding = SSBO_PHOTON_COUNTERS) buffer Counters { uint counters[]; };

uniform int level;
uniform uint firstSeed;
uniform uint seedCount;
uniform uint seed;

void main()
{
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    int side = quadSize >> level;
    if (q.x >= side || q.y >= side) return;
    uint index = quadIndex(level, q);
    uvec2 own;
    if (level == quadLevels) {
        own = uvec2(firstSeed, min(seedCount, uint(quadNodes[index].position.w)));
        seeds[index] = own;
        counters[kCounterSeeds] = own.y;
    } else {
        own = seeds[index];
    }
    if (level == 0) return;

    uint childIndex[4];
    float members[4], weight[4];
    float totalMembers = 0.0, totalEps = 0.0;
    for (int c = 0; c < 4; ++c) {
        childIndex[c] = quadIndex(level - 1, 2 * q + ivec2(c & 1, c >> 1));
        QuadNode child = quadNodes[childIndex[c]];
        members[c] = child.position.w;
        weight[c] = child.normal.w;
        totalMembers += members[c];
        if (members[c] > 0.0) totalEps += weight[c];
    }
    if (!(totalEps > 0.0))
        for (int c = 0; c < 4; ++c) weight[c] = members[c];

    uint given[4] = uint[4](0u, 0u, 0u, 0u);
    uint n = own.y;
    if (n == 1u) {
        // Jittered: one member of the quad at random.
        float r = unitFloat(pcgHash(index ^ pcgHash(seed + uint(level)))) * totalMembers;
        int pick = 3;
        for (int c = 0; c < 4; ++c) {
            if (members[c] > 0.0 && r < members[c]) { pick = c; break; }
            r -= members[c];
        }
        while (members[pick] <= 0.0 && pick > 0) --pick;
        given[pick] = 1u;
    } else if (n > 1u) {
        // Shares in proportion to the weights, capped at the members (water-filling), then rounded.
        bool capped[4] = bool[4](false, false, false, false);
        float share[4] = float[4](0.0, 0.0, 0.0, 0.0);
        float remaining = float(n);
        for (int round = 0; round < 4; ++round) {
            float w = 0.0;
            for (int c = 0; c < 4; ++c)
                if (!capped[c] && members[c] > 0.0) w += max(weight[c], 0.0);
            bool useMembers = !(w > 0.0);
            if (useMembers)
                for (int c = 0; c < 4; ++c)
                    if (!capped[c]) w += members[c];
            bool newlyCapped = false;
            for (int c = 0; c < 4; ++c) {
                if (capped[c] || members[c] <= 0.0) continue;
                share[c] = w > 0.0 ? remaining * (useMembers ? members[c] : max(weight[c], 0.0)) / w : 0.0;
                if (share[c] >= members[c]) {
                    share[c] = members[c];
                    capped[c] = true;
                    newlyCapped = true;
                }
            }
            if (!newlyCapped) break;
            remaining = float(n);
            for (int c = 0; c < 4; ++c)
                if (capped[c]) remaining -= members[c];
            for (int c = 0; c < 4; ++c)
                if (!capped[c]) share[c] = 0.0;
        }
        uint sum = 0u;
        for (int c = 0; c < 4; ++c) {
            given[c] = min(uint(floor(share[c])), uint(members[c]));
            sum += given[c];
        }
        // The rest, one each to the largest remainders among children with room (ties: the first).
        for (int round = 0; round < 8 && sum < n; ++round) {
            int best = -1;
            float bestRest = -1.0;
            for (int c = 0; c < 4; ++c) {
                if (float(given[c]) >= members[c]) continue;
                float rest = share[c] - float(given[c]);
                if (rest > bestRest) { bestRest = rest; best = c; }
            }
            if (best < 0) break;
            given[best] += 1u;
            sum += 1u;
        }
    }
    uint first = own.x;
    for (int c = 0; c < 4; ++c) {
        seeds[childIndex[c]] = uvec2(first, given[c]);
        first += given[c];
    }
}
