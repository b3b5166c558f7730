#version 450 core
// "hierarchy", first dispatch: the leaves, one per point (§2.1: "at the beginning of every frame, we
// recompute the leaf nodes' positions and normals").
#define POINT_SURFELS
#define POINT_RADIANCE
#define POINT_GLOSSY
#include "frame/points/point_cloud.glsl"
#include "technique/microrender/hierarchy.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = SSBO_MICRO_NODES) writeonly buffer MicroNodes { MicroNode microNodes[]; };
uniform uint leafCount;

void main()
{
    uint j = gl_GlobalInvocationID.x;
    if (j >= leafCount) return;
    PointSurfel s = pointSurfels[j];
    MicroNode n;
    n.sphere = vec4(s.position, sqrt(s.areaM2 / kConeAll)); // the disc of the point's area
    n.cone = vec4(s.normal, 0.0);
    n.radiance = pointRadiance[j];
    n.areaM2 = s.areaM2;
    n.pad = 0.0;
#ifdef GLOSSY_POINTS
    n.glossy = pointGlossy[j];
#endif
    microNodes[leafCount + j] = n;
}
