#version 450 core
// Probe relocation and classification (Majercik, Marrs, Spjut & McGuire 2021, sections 4 and 5), from
// this frame's fixed rays of each probe (ddgi_trace.comp), one invocation per probe.
// - RELOCATION: a probe more than a quarter of whose fixed rays see back faces sits inside a solid: it
//   moves through the closest back face, to half the least front-face distance beyond it. A probe whose
//   closest front face is nearer than that least distance moves away from it until it is not. The offset
//   from the grid point stays within 0.45 of the spacing along each axis, so that a probe stays in its
//   cell of the grid.
// - CLASSIFICATION: a probe is active when a fixed ray meets a front face within one grid spacing along
//   every axis (the cells its light reaches) and it does not sit inside a solid; inactive probes cast only
//   their fixed rays, keep their atlases and weigh nothing in the shading (probes.glsl).
#include "technique/ddgi/probes.glsl"
#include "technique/ddgi/rays.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_DDGI_RAYS) readonly buffer DdgiRays { vec4 rays[]; };

uniform int raysPerProbe;
uniform int fixedRays;
uniform int probeCount;
uniform float minFrontDistance; // a front face nearer than this pushes the probe away

void main()
{
    int probe = int(gl_GlobalInvocationID.x);
    if (probe >= probeCount) return;
    int perProbe = fixedRays + raysPerProbe;
    int backfaces = 0;
    float closestBack = 3.0e38, closestFront = 3.0e38;
    vec3 backDirection = vec3(0.0), frontDirection = vec3(0.0);
    bool nearSurface = false;
    for (int r = 0; r < fixedRays; ++r) {
        float d = rays[probe * perProbe + r].a;
        vec3 w = sphericalFibonacci(r, fixedRays);
        if (d < 0.0) {
            ++backfaces;
            float t = -d / kBackfaceShortening;
            if (t < closestBack) { closestBack = t; backDirection = w; }
        } else if (d < kMissDistance) {
            if (d < closestFront) { closestFront = d; frontDirection = w; }
            nearSurface = nearSurface || all(lessThanEqual(abs(w * d), gridSpacing));
        }
    }
    bool inside = float(backfaces) > 0.25 * float(fixedRays);
    vec4 state = probeStates[probe];
#ifdef RELOCATION
    vec3 offset = state.xyz;
    if (inside)
        offset += backDirection * (closestBack + 0.5 * minFrontDistance);
    else if (closestFront < minFrontDistance)
        offset -= frontDirection * (minFrontDistance - closestFront);
    state.xyz = clamp(offset, -0.45 * gridSpacing, 0.45 * gridSpacing);
#endif
#ifdef CLASSIFICATION
    state.w = (nearSurface && !inside) ? 1.0 : 0.0;
#endif
    probeStates[probe] = state;
}
