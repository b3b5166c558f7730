// The radiance a final-gather ray brings back from the surface it hits (section 3.3): the hit point's
// direct light from the frame's shadow maps (common/lighting.glsl), plus its indirect light from the
// photons: the irradiance of the nearby illumination-cut nodes interpolated with Eqs. 4 and 5,
// w_j = K(|p_j - y| / r_j) max(0, n_j . n_y) with K(r) = 1 - r^2 (r <= 1), or, with DENSITY_PHOTONS, a
// nearest-photon density estimate in the full photon map (the reference the cut is measured against).
#ifndef BOUNCE_PHOTON_GATHER_GLSL
#define BOUNCE_PHOTON_GATHER_GLSL

#define SCENE_GEOMETRY
#include "common/lighting.glsl"
#include "common/raycast.glsl"
#include "common/scene_hit.glsl"
#include "technique/photon/cut_lookup.glsl"
#ifdef DENSITY_PHOTONS
#include "technique/photon/density.glsl"
#endif
#include "technique/photon/scatter.glsl"

uniform float rayEpsilon;       // scene units: how far a ray starts off its surface
uniform float causticAlpha;     // CAUSTIC_MAP: the roughest lobe the gather passes its rays on through

// A ray's hit as the gather reads it: the point, its normals facing the ray, its BRDF; `visible` false
// for the back of a one-sided surface, which is black.
struct GatherHit {
    vec3 y, n, ng;
    BrdfParams b;
    bool visible;
};

GatherHit gatherHit(vec3 dir, Hit hit)
{
    SceneHit s = sceneHit(hit);
    GatherHit h;
    h.y = s.p;
    h.ng = s.ng;
    h.n = s.n;
    h.b = s.b;
    h.visible = true;
    if (dot(h.ng, dir) >= 0.0) {
        h.visible = s.m.flags.y != 0;
        h.ng = -h.ng;
        h.n = -h.n;
    }
    if (dot(h.n, dir) >= 0.0) h.n = h.ng;
    return h;
}

// Radiance leaving hit h towards wo: the frame's direct light (lighting.glsl, addDirectLight: in still frames
// the emitters' glossy reflection over their points rotated by `rotation`), as a pixel at h would get it,
// plus photon-map indirect light; emission is left out (the frame's direct light has it). lobe false: the glossy lobe left out of
// both. coverage as CutLookup's (2 with DENSITY_PHOTONS).
vec3 hitRadiance(GatherHit h, vec3 wo, vec2 rotation, bool lobe, out int coverage)
{
    coverage = 2;
    BrdfParams b = h.b;
    if (!lobe) b.weight = 0.0;
    vec3 radiance = vec3(0.0);
    addDirectLight(radiance, h.y, h.n, wo, b, rotation);
#ifdef DENSITY_PHOTONS
    float radius;
    PhotonNode root = photonNodes[1];
    DensitySums s = nearestPhotons(h.y, h.n, nearestStartRadius(root), radius);
    vec3 irradiance = s.power / (kPi * radius * radius);
    vec3 wi = h.n;
#else
    CutLookup c = cutIrradiance(h.y, h.n);
    coverage = c.coverage;
    vec3 irradiance = c.irradiance;
    vec3 wi = dot(c.incoming, h.n) > 0.0 ? c.incoming : h.n;
#endif
    // The photons' irradiance reflected as from one direction, their mean: exact for the Lambertian part.
    return radiance + brdfEval(b, h.n, wo, wi) * irradiance;
}

// Radiance leaving the hit of a ray along `dir` back towards its origin (hitRadiance). With the caustic map
// (CAUSTIC_MAP: lobes no rougher than causticAlpha), a hit on such a lobe passes the ray on once, along a
// direction drawn from the lobe (visible normals; for a mirror, its mirror direction), as the paper's
// shading points seen through specular surfaces: its lobe reflects neither the lights (L S D at the
// origin: the caustic map's) nor the photons' mean direction (a spike for a mirror), but what the passed-on
// ray's hit sends, weighted by the lobe's f cos / pdf.
vec3 gatherRadiance(vec3 dir, Hit hit, vec2 rotation, out int coverage)
{
    coverage = 2;
    GatherHit h = gatherHit(dir, hit);
    if (!h.visible) return vec3(0.0);
#ifdef CAUSTIC_MAP
    bool passOn = h.b.alpha <= causticAlpha;
#else
    bool passOn = false;
#endif
    // A lobe passed on without a diffuse part (a metal) reflects nothing more here.
    vec3 radiance = passOn && !brdfHasDiffuse(h.b) ? vec3(0.0) : hitRadiance(h, -dir, rotation, !passOn, coverage);
#ifdef CAUSTIC_MAP
    // The lobe's sample from the ray's own random pair, hashed apart from the light points it rotates.
    uint r = pcgHash(floatBitsToUint(rotation.x) ^ pcgHash(floatBitsToUint(rotation.y)));
    vec2 u = unitPair(r);
    vec3 wi;
    vec3 f = passOn ? sampleGlossyLobe(h.b, h.n, -dir, u, wi) : vec3(0.0);
    Hit next;
    if (f != vec3(0.0) && dot(h.ng, wi) > 0.0 && closestHit(h.y + h.ng * rayEpsilon, wi, 0.0, 3.0e38, next)) {
        GatherHit g = gatherHit(wi, next);
        int ignored;
        if (g.visible) radiance += f * hitRadiance(g, -wi, rotation, true, ignored);
    }
#endif
    return radiance;
}

#endif
