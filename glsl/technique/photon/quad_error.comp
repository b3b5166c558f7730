#version 450 core
// eps_q of every quadtree node of one level (section 3.2): its members treated as one cluster, centred on
// their mean position and normal, and Eq. 2's error summed over them. Each invocation walks its node's
// pixels in order: every level costs one pass over the image, and the sums are the same in every run.
#include "common/gbuffer.glsl"
#include "technique/photon/shading_clusters.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = SSBO_CLUSTER_OF_PIXEL) readonly buffer ClusterOfPixel { uint clusterOfPixel[]; };

uniform int level;
uniform ivec2 viewport;
uniform int onlyUnclassified;


void main()
{
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    int side = quadSize >> level;
    if (q.x >= side || q.y >= side) return;
    uint index = quadIndex(level, q);
    QuadNode node = quadNodes[index];
    float eps = 0.0;
    if (node.position.w > 1.0) {
        vec3 mean = node.position.xyz / node.position.w;
        vec3 n = meanNormal(node.normal.xyz, node.position.w, vec3(0.0));
        int span = 1 << level;
        ivec2 lo = q * span, hi = min(lo + span, viewport);
        for (int y = lo.y; y < hi.y; ++y)
            for (int x = lo.x; x < hi.x; ++x) {
                GSurface s = gbufferSurface(ivec2(x, y));
                if (!s.geometry) continue;
                if (onlyUnclassified != 0 && clusterOfPixel[y * viewport.x + x] != kUnclassified) continue;
                eps += clusterError(s.position, s.normal, mean, n);
            }
    }
    quadNodes[index].normal.w = eps;
}
