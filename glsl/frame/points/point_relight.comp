#version 450 core
// "relight": one more bounce at the points (micro-rendering §4, "Multiple Bounces with Radiosity": a
// Jacobi iteration that gathers "at an interior node level and then updates the illumination of the
// entire hierarchy"; point projection §4, "Multi-Bounce Indirect Lighting": "treating the scene points as
// shading points ... to update the diffuse radiance at each point"). Point i takes the diffuse light
// gathered at its representative, point (i / stride) x stride (the first point of its run of `stride`:
// in the median-split order a run is one node of the hierarchy, one spatial cluster), times its own
// diffuse colour, on top of its direct light.
#define POINT_SURFELS
#define POINT_RADIANCE
#include "frame/points/point_cloud.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = SSBO_POINT_DIRECT) readonly buffer PointDirect { uvec2 pointDirect[]; };
layout(std430, binding = SSBO_POINT_GATHERED) readonly buffer PointGathered { vec4 pointGathered[]; };
uniform uint pointCount;
uniform uint stride;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= pointCount) return;
    vec3 gathered = pointGathered[i / stride].rgb; // the gather's diffuse part, without the albedo
    vec3 diffuse = unpackUnorm4x8(pointSurfels[i].diffuse).rgb;
    pointRadiance[i] = packRadiance(unpackRadiance(pointDirect[i]) + diffuse * gathered);
}
