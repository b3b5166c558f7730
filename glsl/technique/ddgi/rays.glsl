// The directions of a probe's rays (Majercik et al. 2019, section 5.1: a spherical Fibonacci set under a
// random rotation each frame; 2021, section 4: a fixed set beside it for relocation and classification),
// shared by the pass that casts them (ddgi_trace.comp) and those that read them back.
#ifndef BOUNCE_DDGI_RAYS_GLSL
#define BOUNCE_DDGI_RAYS_GLSL

const float kMissDistance = 1.0e27;     // a miss's distance (the moments clamp it to maxDistance)
const float kBackfaceShortening = 0.2;  // a back face's distance is kept as -0.2 t (2021, section 4)

// Point i of the spherical Fibonacci set of n points: z evenly spaced in (-1, 1), the azimuth stepping by
// the golden angle.
vec3 sphericalFibonacci(int i, int n)
{
    const float kGoldenFraction = 0.61803398874989485;
    float phi = 2.0 * 3.14159265358979323846 * fract(float(i) * kGoldenFraction);
    float z = 1.0 - (2.0 * float(i) + 1.0) / float(n);
    float r = sqrt(max(1.0 - z * z, 0.0));
    return vec3(r * cos(phi), r * sin(phi), z);
}

// Ray `ray` of a probe: the fixed set first, then the rotated one.
vec3 probeRayDirection(int ray, int fixedRays, int raysPerProbe, mat3 rotation)
{
    if (ray < fixedRays) return sphericalFibonacci(ray, fixedRays);
    return normalize(rotation * sphericalFibonacci(ray - fixedRays, raysPerProbe));
}

#endif
