// A cluster's members as the k-means passes after the sort read them, one invocation per cluster
// (kmeans_update.comp, kmeans_sample.comp): a range of the pixel list sorted by cluster.
#ifndef BOUNCE_KMEANS_MEMBERS_GLSL
#define BOUNCE_KMEANS_MEMBERS_GLSL

#include "common/gbuffer.glsl"
#include "technique/photon/shading_clusters.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_SORT_VALUES) readonly buffer Values { uint sortedPixels[]; };

uniform uint clusterCount;
uniform ivec2 viewport;

// Cluster k's members' range [x, y) in sortedPixels, cleared in the cluster ((0, 0) between uses). A
// cluster without members drops out (centre.w = 0).
uvec2 takeMembers(uint k)
{
    uvec2 range = clusters[k].members.xy;
    clusters[k].members = uvec4(0u);
    if (range.y <= range.x) clusters[k].centre.w = 0.0;
    return range;
}

// The pixel of an entry of sortedPixels (y * width + x).
ivec2 memberPixel(uint p) { return ivec2(int(p % uint(viewport.x)), int(p / uint(viewport.x))); }

#endif
