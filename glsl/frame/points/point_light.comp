#version 450 core
// "point-light": direct light at every point from the frame's shadow maps, stored as half floats
// (micro-rendering §4, "One-Bounce Indirect Illumination": "directly lighting the point hierarchy, e.g.
// using shadow mapping techniques"; point projection §4, "Primary Lights"). With bounces > 1 the direct
// part is kept apart too, for point_relight.comp to add gathered light to.
#define POINT_SURFELS
#define POINT_RADIANCE
#include "frame/points/point_cloud.glsl"
#include "frame/points/point_light.glsl"

layout(local_size_x = 64) in;
#ifdef KEEP_DIRECT
layout(std430, binding = SSBO_POINT_DIRECT) writeonly buffer PointDirect { uvec2 pointDirect[]; };
#endif
uniform uint pointCount;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= pointCount) return;
    PointSurfel s = pointSurfels[i];
    uvec2 h = packRadiance(pointDirectRadiance(s.position, s.normal, unpackUnorm4x8(s.diffuse).rgb));
    pointRadiance[i] = h;
#ifdef KEEP_DIRECT
    pointDirect[i] = h;
#endif
}
