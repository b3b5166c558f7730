#version 450 core
// Probe rays (Majercik et al. 2019, section 5.1; Majercik et al. 2021, section 4): one invocation per probe
// and ray, cast through the frame's BVH (common/raycast.glsl). Rays 0 .. fixedRays-1 of every probe take
// fixed directions (a spherical Fibonacci set of fixedRays, never rotated), which relocation and
// classification read (ddgi_probe_state.comp); the others, raysPerProbe of them, a spherical Fibonacci set
// under this frame's random rotation, which the atlases blend (ddgi_update.comp). An inactive probe casts
// only its fixed rays.
//
// At a front-facing hit the ray brings back the frame's direct light there (common/lighting.glsl, the
// estimator of the G-buffer's pixels, shadow maps or rays included) and, with BOUNCES, the hit's diffuse
// reflection of the irradiance the probes held last frame (the paper's infinite bounces, one per frame). A
// hit on an emitter adds none of its emission: the frame's direct light carries the emitters' light to every
// pixel, so the probes hold indirect light only. A miss brings back black at an unbounded distance. A back
// face of a one-sided surface (the inside of a solid) brings back black, and its distance negative and
// shortened by the 2021 paper's factor 0.2, so that the distance moments keep probes inside solids from the
// surfaces outside.
#define SCENE_GEOMETRY
#define DDGI_SHADING
#include "common/lighting.glsl"
#include "common/random.glsl"
#include "common/scene_hit.glsl"
#include "technique/ddgi/probes.glsl"
#include "technique/ddgi/rays.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_DDGI_RAYS) writeonly buffer DdgiRays { vec4 rays[]; };

uniform int raysPerProbe;  // rotated rays per probe
uniform int fixedRays;     // fixed rays per probe (0 without relocation and classification)
uniform mat3 rayRotation;  // this frame's random rotation of the rotated rays
uniform uint seed;         // this frame's: the area lights' sample points at the hits

void main()
{
    int ray = int(gl_GlobalInvocationID.x), probe = int(gl_GlobalInvocationID.y);
    int perProbe = fixedRays + raysPerProbe;
    if (ray >= perProbe) return;
    int k = probe * perProbe + ray;
    if (ray >= fixedRays && !probeActive(probe)) {
        rays[k] = vec4(0.0);
        return;
    }
    vec3 d = probeRayDirection(ray, fixedRays, raysPerProbe, rayRotation);
    vec3 o = probePosition(probe);
    Hit hit;
    if (!closestHit(o, d, 0.0, 3.0e38, hit)) {
        rays[k] = vec4(0.0, 0.0, 0.0, kMissDistance);
        return;
    }
    SceneHit h = sceneHit(hit);
    vec3 n = h.n;
    if (dot(h.ng, d) > 0.0) {
        if (h.m.flags.y == 0) {
            rays[k] = vec4(0.0, 0.0, 0.0, -kBackfaceShortening * hit.t);
            return;
        }
        n = -n; // a two-sided surface's back: lit as its front
    }
    vec3 wo = -d, p = h.p;
    vec3 radiance = vec3(0.0);
    addDirectLight(radiance, p, n, wo, h.b, unitPair(hashU(seed ^ hashU(uint(k)))));
#ifdef BOUNCES
    radiance += h.b.diffuse / kPi * ddgiIrradiance(p, n, wo) * brdfTransmission(h.b, max(dot(n, wo), 0.0)) *
                brdfMeanTransmission(h.b);
#endif
    rays[k] = vec4(radiance, hit.t);
}
