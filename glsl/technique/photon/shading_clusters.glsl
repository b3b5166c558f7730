// Shading clusters (section 3.2; gl/technique/photon/shading_clusters.h): the error metric of Eq. 2 and the
// clusters' layout. The screen-space quadtree the seeds are placed over (cluster_quadtree.glsl) and the tree
// of cluster centres (or samples) that nearest-centre searches and the interpolation walk
// (cluster_point_tree.glsl) have files of their own, so that a pass declares only the blocks it reads.
#ifndef BOUNCE_SHADING_CLUSTERS_GLSL
#define BOUNCE_SHADING_CLUSTERS_GLSL

#include "technique/photon/photon.glsl"

// One shading cluster: its centre (mean position and normal of its members), its members' range in the
// pixel list sorted by cluster, its irradiance sample (the member nearest the centre by Eq. 2) and what
// the final gather measured there.
struct Cluster {
    vec4 centre;       // xyz mean member position, w: members
    vec4 normal;       // xyz unit mean member normal, w: the largest member error (temporal reuse)
    vec4 samplePoint;     // xyz the sample's position, w: its pixel index (exact in float to 2^24), or -1.0 when the cluster is empty
    vec4 sampleNormal; // xyz the sample's normal, w: unused
    vec4 irradiance;   // rgb E at the sample (final gather), w: R_j, the harmonic mean distance of its rays
    uvec4 members;     // x, y: its members' range [x, y) in the pixel list sorted by cluster (0, 0 between uses)
};

const uint kNoCluster = 0xFFFFFFFFu;    // a pixel without geometry
const uint kUnclassified = 0xFFFFFFFEu; // temporal reuse: no previous cluster takes the pixel

// The clusters' block, unless the pass declares its own (CLUSTERS_CUSTOM) or reads no cluster
// (CLUSTERS_UNUSED: it takes the layout, the constants and Eq. 2 only; a declared block must be bound).
#if !defined(CLUSTERS_CUSTOM) && !defined(CLUSTERS_UNUSED)
layout(std430, binding = SSBO_CLUSTER_CENTRES) buffer Clusters { Cluster clusters[]; };
#endif

uniform float alpha; // Eq. 2's weight of position, already divided by the scene's size (1/m)

// Eq. 2: eps = alpha |x_i - x_k| + sqrt(2 - 2 n_i . n_k). For unit normals the square root is the chord
// |n_i - n_k|, which is written so: sqrt(2 - 2 n_i . n_k) turns one ulp of the dot product of two equal
// normals into 3.5e-4, enough to hand a point between two clusters of one wall to either (an NVIDIA
// H200 decoded a normal an ulp apart in a compute and a fragment shader). A centre without a normal
// (opposite normals cancelled: meanNormal's zero fallback) keeps Eq. 2's value, sqrt(2).
float clusterError(vec3 x, vec3 n, vec3 xk, vec3 nk)
{
    float normalTerm = dot(nk, nk) > 0.5 ? length(n - nk) : sqrt(max(0.0, 2.0 - 2.0 * dot(n, nk)));
    return alpha * length(x - xk) + normalTerm;
}

// The mean of summed unit normals; when they cancel (a cluster of opposite normals), `fallback`.
vec3 meanNormal(vec3 sum, float count, vec3 fallback)
{
    float len = length(sum);
    return len > 1e-3 * max(count, 1.0) ? sum / len : fallback;
}

#endif
