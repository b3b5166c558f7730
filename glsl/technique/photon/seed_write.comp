#version 450 core
// The seeds become the first cluster centres: the pixel a seed reached at the quadtree's bottom.
#include "common/gbuffer.glsl"
#include "technique/photon/cluster_quadtree.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = SSBO_CLUSTER_SEEDS) readonly buffer Seeds { uvec2 seeds[]; };

uniform ivec2 viewport;

void main()
{
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (q.x >= viewport.x || q.y >= viewport.y) return;
    uvec2 s = seeds[quadIndex(0, q)];
    if (s.y == 0u) return;
    GSurface g = gbufferSurface(q);
    vec3 n = g.normal;
    clusters[s.x].centre = vec4(g.position, 1.0);
    clusters[s.x].normal = vec4(n, 0.0);
    clusters[s.x].samplePoint = vec4(0.0, 0.0, 0.0, -1.0);
    clusters[s.x].sampleNormal = vec4(n, 0.0);
    clusters[s.x].irradiance = vec4(0.0);
    clusters[s.x].members = uvec4(0u);
}
