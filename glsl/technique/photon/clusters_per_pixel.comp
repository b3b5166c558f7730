#version 450 core
// Gathering at every pixel (Fig. 6's references for the clustering's error): each shading point is its
// own cluster and its own sample.
#include "common/gbuffer.glsl"
#include "technique/photon/shading_clusters.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = SSBO_CLUSTER_OF_PIXEL) writeonly buffer ClusterOfPixel { uint clusterOfPixel[]; };

uniform ivec2 viewport;

void main()
{
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (q.x >= viewport.x || q.y >= viewport.y) return;
    uint p = uint(q.y * viewport.x + q.x);
    GSurface s = gbufferSurface(q);
    vec3 n = s.normal;
    bool valid = s.geometry;
    clusters[p].centre = vec4(s.position, valid ? 1.0 : 0.0);
    clusters[p].normal = vec4(n, 0.0);
    clusters[p].samplePoint = vec4(s.position, valid ? float(p) : -1.0);
    clusters[p].sampleNormal = vec4(n, 0.0);
    clusters[p].irradiance = vec4(0.0);
    clusters[p].members = uvec4(0u);
    clusterOfPixel[p] = valid ? p : kNoCluster;
}
