#version 450 core
// eps_q of every quadtree node of one level (section 3.2): its members treated as one cluster, centred on
// their mean position and normal, and Eq. 2's error summed over them. Every level costs one pass over the
// image, in one of two forms (ShadingClusters::buildQuadtree chooses by the node's span):
// - small nodes (QUAD_GROUP undefined): one invocation per node walks its pixels in order;
// - large nodes (QUAD_GROUP, span above 16 pixels): one work group of QUAD_GROUP invocations per node,
//   invocation t summing the node's pixels t, t + QUAD_GROUP, ... (neighbouring invocations read
//   neighbouring pixels), then a tree reduction in shared memory. One invocation walking the root's
//   whole image took most of a 512x512 still frame's k-means on an NVIDIA H200 (52 ms against 10).
// Either way the order of the sums is fixed: the same eps_q in every run.
#include "common/gbuffer.glsl"
#define CLUSTERS_UNUSED
#include "technique/photon/cluster_quadtree.glsl"

#ifdef QUAD_GROUP
layout(local_size_x = QUAD_GROUP) in;
#define GROUP_SUM_TYPE float
#define GROUP_SUM_SIZE QUAD_GROUP
#include "common/group_sum.glsl"
#else
layout(local_size_x = 8, local_size_y = 8) in;
#endif

layout(std430, binding = SSBO_CLUSTER_OF_PIXEL) readonly buffer ClusterOfPixel { uint clusterOfPixel[]; };

uniform int level;
uniform ivec2 viewport;
uniform int onlyUnclassified;

// Eq. 2's error of pixel p to the node's mean, 0 for a pixel that is not a member.
float memberError(ivec2 p, vec3 mean, vec3 n)
{
    if (any(greaterThanEqual(p, viewport))) return 0.0;
    GSurface s = gbufferSurface(p);
    if (!s.geometry) return 0.0;
    if (onlyUnclassified != 0 && clusterOfPixel[p.y * viewport.x + p.x] != kUnclassified) return 0.0;
    return clusterError(s.position, s.normal, mean, n);
}

void main()
{
    int side = quadSize >> level, span = 1 << level;
#ifdef QUAD_GROUP
    ivec2 q = ivec2(gl_WorkGroupID.xy);
    uint t = gl_LocalInvocationID.x;
#else
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
#endif
    if (q.x >= side || q.y >= side) return; // (whole work groups: the barriers below stay uniform)
    uint index = quadIndex(level, q);
    QuadNode node = quadNodes[index];
    float eps = 0.0;
    ivec2 lo = q * span;
    bool members = node.position.w > 1.0;
    vec3 mean = members ? node.position.xyz / node.position.w : vec3(0.0);
    vec3 n = members ? meanNormal(node.normal.xyz, node.position.w, vec3(0.0)) : vec3(0.0);
#ifdef QUAD_GROUP
    // The node's pixels that lie in the image, row by row.
    ivec2 hi = min(lo + span, viewport);
    if (members && all(lessThan(lo, hi))) {
        uint width = uint(hi.x - lo.x), count = width * uint(hi.y - lo.y);
        for (uint i = t; i < count; i += uint(QUAD_GROUP))
            eps += memberError(lo + ivec2(i % width, i / width), mean, n);
    }
    eps = groupSum(eps);
    if (t == 0u) quadNodes[index].normal.w = eps;
#else
    if (members) {
        ivec2 hi = min(lo + span, viewport);
        for (int y = lo.y; y < hi.y; ++y)
            for (int x = lo.x; x < hi.x; ++x) eps += memberError(ivec2(x, y), mean, n);
    }
    quadNodes[index].normal.w = eps;
#endif
}
