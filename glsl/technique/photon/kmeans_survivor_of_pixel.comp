#version 450 core
// Temporal reuse: each pixel the classification kept, in the cluster it joined (its nearest previous
// centre, which therefore survived), numbered as the survivors now are (the marks scanned into positions);
// kUnclassified for the others. kmeans_assign.comp starts every k-means iteration of the frame from it.
#define CLUSTERS_UNUSED
#include "technique/photon/shading_clusters.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_CLUSTER_OF_PIXEL) readonly buffer ClusterOfPixel { uint clusterOfPixel[]; };
layout(std430, binding = SSBO_SCAN) readonly buffer Positions { uint positions[]; };
// Borrowed slot: the seeds are not bound while the iterations run.
layout(std430, binding = SSBO_CLUSTER_SEEDS) writeonly buffer SurvivorOfPixel { uint survivorOfPixel[]; };

uniform uint pixelCount;
uniform uint previousCount; // clusters of the previous frame, before the survivors were compacted

void main()
{
    uint p = gl_GlobalInvocationID.x;
    if (p >= pixelCount) return;
    uint c = clusterOfPixel[p];
    survivorOfPixel[p] = c < previousCount ? positions[c] : kUnclassified;
}
