#version 450 core
// The quadtree's pixels (section 3.2, "Adaptive Seeding"): a shading point is a pixel with geometry;
// with onlyUnclassified, only those that temporal reuse left without a cluster (kmeans_classify.comp).
#include "common/gbuffer.glsl"
#define CLUSTERS_UNUSED
#include "technique/photon/cluster_quadtree.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = SSBO_CLUSTER_OF_PIXEL) readonly buffer ClusterOfPixel { uint clusterOfPixel[]; };

uniform ivec2 viewport;
uniform int onlyUnclassified;


void main()
{
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (q.x >= quadSize || q.y >= quadSize) return;
    QuadNode node = QuadNode(vec4(0.0), vec4(0.0));
    if (q.x < viewport.x && q.y < viewport.y) {
        GSurface s = gbufferSurface(q);
        bool member = s.geometry;
        if (onlyUnclassified != 0) member = member && clusterOfPixel[q.y * viewport.x + q.x] == kUnclassified;
        if (member) node = QuadNode(vec4(s.position, 1.0), vec4(s.normal, 0.0));
    }
    quadNodes[quadIndex(0, q)] = node;
}
