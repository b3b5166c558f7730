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
#include "technique/photon/pixel_pass.glsl"
#include "technique/photon/photon_gather.glsl"
#include "technique/photon/photon.glsl"
#include "technique/photon/scatter.glsl"

uniform uint rayIndex; // this dispatch's ray, of rayCount per pixel
uniform uint rayCount;
uniform uint seed;     // a new set of directions for every still frame

void main()
{
    PixelPoint s;
    if (!loadPixelPoint(s) || s.b.weight <= 0.0 || dot(s.n, s.wo) <= 0.0) return;
    // Ray j of the pixel's stratified set (rows of a Hammersley set), the set rotated per pixel and frame.
    uint h = pcgHash(uint(s.q.y * viewport.x + s.q.x) ^ pcgHash(seed));
    vec2 shift = unitPair(h);
    vec2 u = fract(vec2((float(rayIndex) + 0.5) / float(rayCount), radicalInverse2(rayIndex)) + shift);
    vec3 wi;
    vec3 weight = sampleGlossyLobe(s.b, s.n, s.wo, u, wi);
    Hit hit;
    if (weight == vec3(0.0) || !closestHit(s.x + s.n * rayEpsilon, wi, 0.0, 3.0e38, hit)) return;
    int coverage;
    uint r = pcgHash(pcgHash(h) ^ (rayIndex + 1u));
    vec2 rotation = unitPair(r);
    addToPixel(s.q, weight * gatherRadiance(wi, hit, rotation, coverage) / float(rayCount));
}
