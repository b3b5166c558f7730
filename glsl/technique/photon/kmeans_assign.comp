#version 450 core
// k-means, classification (section 3.2): every shading point to its nearest centre by Eq. 2, found
// through the tree of centres: a subtree is skipped when a lower bound of Eq. 2 over it (pointNodeBound:
// alpha times the distance to its box plus the distance from the normal to its normals' box) exceeds the
// best error so far; the previous assignment's error starts the bound. Ties go to the lower cluster
// index, so the result is the brute force's (bruteForce: every centre, for tests). Writes the cluster and
// the (cluster, pixel) pair the sort by cluster takes, and with countMoves counts the pixels whose cluster
// changed (k-means has converged when none did).
// With temporal reuse the survivors' centres stay where they are for the whole frame (kmeans_update.comp):
// a pixel the classification kept is nearer its survivor than any other survivor (the classification's
// nearest previous centre, ties to the lower index, which the survivors' order keeps), so its nearest
// centre is that survivor or one of the new clusters, all of which are tried (fixedClusters > 0). The
// result is the walk's, bit for bit; the walk remains for the other pixels, and for a pixel whose survivor
// has lost all its members (it drops out, and the next survivor is unknown).
#include "common/gbuffer.glsl"
#include "technique/photon/cluster_point_tree.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = SSBO_CLUSTER_OF_PIXEL) buffer ClusterOfPixel { uint clusterOfPixel[]; };
layout(std430, binding = SSBO_SORT_KEYS) writeonly buffer Keys { uint keys[]; };
layout(std430, binding = SSBO_SORT_VALUES) writeonly buffer Values { uint values[]; };
layout(std430, binding = SSBO_PHOTON_COUNTERS) buffer Counters { uint counters[]; };
// kmeans_survivor_of_pixel.comp's output (the seeds' slot, borrowed).
layout(std430, binding = SSBO_CLUSTER_SEEDS) readonly buffer SurvivorOfPixel { uint survivorOfPixel[]; };

uniform ivec2 viewport;
uniform uint clusterCount;
uniform int bruteForce;
uniform int onlyClassify;   // temporal reuse: keep a pixel only when its error is within the cluster's largest
uniform float errorSlack;   //   (times 1 + errorSlack), else mark it unclassified
uniform int countMoves;     // count the pixels whose cluster changed in counters[kCounterFirst]
uniform uint fixedClusters; // > 0: clusters [0, fixedClusters) are survivors whose centres stay, and
                            //   survivorOfPixel holds each kept pixel's

void consider(uint c, vec3 x, vec3 n, inout float best, inout uint bestCluster)
{
    Cluster k = clusters[c];
    if (k.centre.w <= 0.0) return;
    float e = clusterError(x, n, k.centre.xyz, k.normal.xyz);
    if (e < best || (e == best && c < bestCluster)) {
        best = e;
        bestCluster = c;
    }
}

void main()
{
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (q.x >= viewport.x || q.y >= viewport.y) return;
    uint pixel = uint(q.y * viewport.x + q.x);
    GSurface s = gbufferSurface(q);
    uint bestCluster = kNoCluster, previous = clusterOfPixel[pixel];
    if (s.geometry) {
        vec3 x = s.position, n = s.normal;
        float best = 3.0e38;
        uint survivor = fixedClusters > 0u ? survivorOfPixel[pixel] : kUnclassified;
        if (bruteForce != 0) {
            for (uint c = 0u; c < clusterCount; ++c) consider(c, x, n, best, bestCluster);
        } else if (survivor < fixedClusters && clusters[survivor].centre.w > 0.0) {
            consider(survivor, x, n, best, bestCluster);
            for (uint c = fixedClusters; c < clusterCount; ++c) consider(c, x, n, best, bestCluster);
        } else {
            if (previous < clusterCount) consider(previous, x, n, best, bestCluster);
            uint i = 1u;
            while (i != 0u) {
                PointNode node = pointNodes[i];
                if (node.lo.w <= 0.0 || pointNodeBound(x, n, node) * (1.0 - 1e-5) > best) {
                    i = pointSkip(i);
                } else if (findMSB(i) == pointTreeDepth) {
                    consider(floatBitsToUint(node.hi.w), x, n, best, bestCluster);
                    i = pointSkip(i);
                } else {
                    i = 2u * i;
                }
            }
        }
        if (onlyClassify != 0 && bestCluster != kNoCluster &&
            best > clusters[bestCluster].normal.w * (1.0 + errorSlack) + 1e-6)
            bestCluster = kUnclassified;
        if (bestCluster == kNoCluster) bestCluster = kUnclassified;
    }
    if (countMoves != 0 && bestCluster != previous) atomicAdd(counters[kCounterFirst], 1u);
    clusterOfPixel[pixel] = bestCluster;
    keys[pixel] = bestCluster < clusterCount ? bestCluster : clusterCount;
    values[pixel] = pixel;
}
