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
//   glossy  GLOSSY_POINTS: its points' glossy lobes as one (point_cloud.glsl's `glossy`; 64 bytes a node):
//           the area-weighted mean of their weighted irradiance, and the mean of their directions to the
//           light, F0 and sqrt(alpha) weighted by area times that irradiance's luminance, so that unlit
//           and diffuse points (weight 0) do not dilute the lobe of the lit metal beside them. The lobe is
//           evaluated about the node's cone axis (an approximation above the leaves, as its radiance is).
#ifndef BOUNCE_MICRO_HIERARCHY_GLSL
#define BOUNCE_MICRO_HIERARCHY_GLSL

#include "frame/points/point_cloud.glsl"
#include "technique/microrender/bindings.glsl"

struct MicroNode {
    vec4 sphere;     // xyz centre, w radius
    vec4 cone;       // xyz unit axis, w half angle
    uvec2 radiance;  // RGB half floats (point_cloud.glsl: packRadiance)
    float areaM2;
    float pad;
#ifdef GLOSSY_POINTS
    uvec4 glossy;
#endif
};

const float kConeAll = 3.14159265358979323846;

// What node nd sends towards wo (unit, from the node towards the gatherer): its stored radiance, and the
// glossy lobe's direct light seen from wo.
vec3 nodeRadiance(MicroNode nd, vec3 wo)
{
#ifdef GLOSSY_POINTS
    return unpackRadiance(nd.radiance) + pointGlossyRadiance(nd.glossy, nd.cone.xyz, wo);
#else
    return unpackRadiance(nd.radiance);
#endif
}

#ifdef GLOSSY_POINTS
// A node whose glossy lobe outshines its diffuse light and whose normals spread wider than that lobe (its
// cone's half angle above sqrt(alpha), radians): one lobe about the cone's axis would send the light where
// none of its points does (a node over the edge of cornell-glossy's metal block, its axis between the top
// and a side, lit the back wall with light the top sends to the ceiling). The cut refines such nodes.
// "Outshines": the lobe's peak, F0 E D(1) Vis(1, 1) = F0 E / (4 pi alpha^2), above the diffuse radiance;
// a rough dielectric's faint lobe (Sponza: F0 0.04) does not, and its nodes are not refined for it
// (refining them all took 1.8x the nodes per sample there).
bool glossyTooWide(MicroNode nd)
{
    vec4 m = unpackUnorm4x8(nd.glossy.w);
    if (nd.cone.w <= m.a) return false;
    float alpha = glossyAlpha(m);
    float peak = dot(m.rgb, kLuminance) * dot(glossyIrradiance(nd.glossy), kLuminance) / (4.0 * kPi * alpha * alpha);
    return peak > dot(unpackRadiance(nd.radiance), kLuminance);
}

// Two nodes' glossy lobes as one (above); wa the first's share of the area.
uvec4 mergeGlossy(uvec4 a, uvec4 b, float wa)
{
    vec3 ea = glossyIrradiance(a), eb = glossyIrradiance(b);
    float la = wa * dot(ea, kLuminance), lb = (1.0 - wa) * dot(eb, kLuminance);
    float ta = la + lb > 0.0 ? la / (la + lb) : 0.5;
    vec3 direction = ta * unpackUnitVector(a.x) + (1.0 - ta) * unpackUnitVector(b.x);
    direction = dot(direction, direction) > 1e-12 ? normalize(direction) : unpackUnitVector(a.x);
    vec4 material = ta * unpackUnorm4x8(a.w) + (1.0 - ta) * unpackUnorm4x8(b.w);
    return packGlossy(direction, wa * ea + (1.0 - wa) * eb, packUnorm4x8(material));
}
#endif

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
