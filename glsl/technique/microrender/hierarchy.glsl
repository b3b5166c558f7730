// Micro-rendering's point hierarchy (Ritschel et al. 2009, §2.1 and §3.1): a complete binary tree over the
// point cloud in its median-split order (core/point_order.h), stored implicitly in heap order: the root is
// node 1, the children of node i are 2i and 2i + 1, leaf j is node leafCount + j (leafCount a power of two),
// so no child or skip pointers are stored ("this enables us to compute skip-pointers on-the-fly").
// Per node (§3.1 packs it into 128 bits; here 48 bytes of floats and halves):
//   sphere  centre and radius: a leaf is the point's disc, r = sqrt(area / pi); an interior node the
//           smallest sphere around its two children's spheres
//   cone    the cone of normals, axis and half angle (radians; pi: every direction)
//   radiance the area-weighted mean outgoing radiance of its points, half floats ("we opt for storing the
//           reflected radiance as half-floats")
//   area    the summed area of its points (m^2)
#ifndef BOUNCE_MICRO_HIERARCHY_GLSL
#define BOUNCE_MICRO_HIERARCHY_GLSL

#include "technique/microrender/bindings.glsl"

struct MicroNode {
    vec4 sphere;     // xyz centre, w radius
    vec4 cone;       // xyz unit axis, w half angle
    uvec2 radiance;  // RGB half floats (point_cloud.glsl: packRadiance)
    float areaM2;
    float pad;
};

const float kConeAll = 3.14159265358979323846;

// The smallest sphere around two spheres, a little larger so that float rounding never leaves a child
// outside (tests/gl/microrender_test.cpp checks containment).
vec4 mergeSpheres(vec4 a, vec4 b)
{
    vec3 d = b.xyz - a.xyz;
    float dist = length(d);
    if (dist + b.w <= a.w) return a;
    if (dist + a.w <= b.w) return b;
    float r = 0.5 * (dist + a.w + b.w);
    vec3 c = a.xyz + d * ((r - a.w) / dist);
    return vec4(c, r * (1.0 + 1e-6) + 1e-7 * length(c));
}

// The smallest cone around two cones of normals (axis, half angle).
vec4 mergeCones(vec4 a, vec4 b)
{
    if (a.w >= kConeAll) return a;
    if (b.w >= kConeAll) return b;
    float phi = acos(clamp(dot(a.xyz, b.xyz), -1.0, 1.0));
    if (phi + b.w <= a.w) return a;
    if (phi + a.w <= b.w) return b;
    float halfAngle = 0.5 * (phi + a.w + b.w);
    if (halfAngle >= kConeAll) return vec4(a.xyz, kConeAll);
    // Turn a's axis towards b's by half - a.w in their common plane.
    vec3 side = b.xyz - a.xyz * dot(a.xyz, b.xyz);
    float len = length(side);
    if (len < 1e-6) return vec4(a.xyz, kConeAll); // opposite axes: no plane, no smaller cone worth finding
    float turn = halfAngle - a.w;
    vec3 axis = normalize(a.xyz * cos(turn) + (side / len) * sin(turn));
    return vec4(axis, min(halfAngle * (1.0 + 1e-5) + 1e-5, kConeAll));
}

#endif
