#version 450 core
// The glossy last bounce by sampling the lobe at every pixel, where the paper interpolates spherical
// harmonics at the clusters' samples (section 3.4; README, Departures). At a pixel whose material has a
// glossy lobe, one direction drawn from the lobe (GGX visible normals, Heitz 2018) per dispatch; the ray
// brings back what a final-gather ray does (photon_gather.glsl: its hit's direct light from the shadow maps
// plus the hit's photon light from the illumination cut), weighted by the lobe's f cos / pdf, and a
// `1 / rayCount` share of it is added to the indirect light the interpolation wrote (which then leaves the
// lobe's split-sum albedo out: GLOSSY_SAMPLED in photon_interpolate.glsl). Emission at the hit is left out:
// the frame's direct light reflects the emitters in the lobe already. One ray per invocation and dispatch:
// llvmpipe's loop limiter ends an invocation's loops after 65,535 iterations together (photon_gather.comp).
#include "common/gbuffer.glsl"
#include "technique/photon/photon_gather.glsl"
#include "technique/photon/photon.glsl"
#include "technique/photon/scatter.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform image2D target;

uniform ivec2 viewport;
uniform vec3 cameraPosition;
uniform uint rayIndex; // this dispatch's ray, of rayCount per pixel
uniform uint rayCount;
uniform uint seed;     // a new set of directions for every still frame

void main()
{
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(q, viewport))) return;
    GSurface g = gbufferSurface(q);
    if (!g.geometry) return;
    BrdfParams b = gbufferBrdf(q);
    vec3 n = g.normal, x = g.position;
    vec3 wo = normalize(cameraPosition - x);
    if (b.weight <= 0.0 || dot(n, wo) <= 0.0) return;
    // Ray j of the pixel's stratified set (rows of a Hammersley set), the set rotated per pixel and frame.
    uint h = pcgHash(uint(q.y * viewport.x + q.x) ^ pcgHash(seed));
    vec2 shift = vec2(float(h >> 8), float(pcgHash(h) >> 8)) * (1.0 / 16777216.0);
    vec2 u = fract(vec2((float(rayIndex) + 0.5) / float(rayCount), radicalInverse2(rayIndex)) + shift);
    vec3 wi;
    vec3 weight = sampleGlossyLobe(b, n, wo, u, wi);
    Hit hit;
    if (weight == vec3(0.0) || !closestHit(x + n * rayEpsilon, wi, 0.0, 3.0e38, hit)) return;
    int coverage;
    uint r = pcgHash(pcgHash(h) ^ (rayIndex + 1u));
    vec2 rotation = vec2(float(r >> 8), float(pcgHash(r) >> 8)) * (1.0 / 16777216.0);
    vec3 radiance = weight * gatherRadiance(wi, hit, rotation, coverage) / float(rayCount);
    vec4 sum = imageLoad(target, q);
    imageStore(target, q, vec4(sum.rgb + radiance, sum.a));
}
