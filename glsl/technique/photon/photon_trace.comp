#version 450 core
// Photon tracing (section 3.1, "Building Photon Maps"): one invocation per photon path. The path's
// emitter is the light whose photon range holds its index (PhotonEmitter, photon_tracer.h: ranges in
// proportion to power); it leaves the light with that light's power over its photon count, is traced
// through the frame's BVH (common/raycast.glsl), and at every surface it reaches:
//   - an emitter, or the back of a one-sided surface, absorbs it (both are black);
//   - from the second surface on it is stored (the first surface's light is direct light, which the
//     frame's shadow maps give: the photon map holds indirect light only);
//   - it scatters by the BRDF (scatter.glsl), with Russian roulette on the ratio of its power after and
//     before, so that a surviving photon keeps its power and the stored power is unbiased; at the first
//     surface only for the light kinds firstSurfaceRoulette names (a directional light's guided photons
//     take the bounce's weight there instead: PhotonTracerSettings::firstSurfaceRoulette);
//   - a photon whose every bounce so far drew the glossy lobe of a near-specular surface (GGX alpha at
//     most causticAlpha) is a caustic photon, L S+ D (Jensen 2001): stored with incoming.w = 1, read at the
//     pixels by photon_caustic.comp.
// Photons are appended in any order with (path, index within the path); photon_place.comp puts them in
// path order afterwards, so the photon map is the same in every run. DIRECTIONAL_LIGHTS: the scene has a
// directional light (its projection-map emission is compiled only then: llvmpipe pays for a texel fetch
// in a branch no path takes, 71 against 289 ms on cornell-spot).
#define SCENE_GEOMETRY
#include "common/scene.glsl"
#include "common/raycast.glsl"
#include "common/scene_hit.glsl"
#include "technique/photon/photon.glsl"
#include "technique/photon/scatter.glsl"

layout(local_size_x = 64) in;

struct PhotonEmitter {
    vec4 positionType;   // xyz position (point, spot), the projection map's corner (directional); w: kLight* kind
    vec4 directionCos;   // xyz the direction light travels (spot, directional) or the emitter normal (area); w: cos outer
    vec4 powerCosInner;  // rgb W per photon (before a spot's falloff); w: cos inner
    vec4 v0;             // area: corner 0; directional: xyz the map's first axis, w its cell side
    vec4 v1;             // area: corner 1; directional: xyz the second axis, w the grid size
    vec4 v2;             // area: corner 2; directional: x its emission list's entries, y the first of them in
                         // projectionCells, z entries / cells
    uvec4 range;         // x: first path index, y: path count
};

layout(std430, binding = SSBO_PHOTON_EMITTERS) readonly buffer Emitters { PhotonEmitter emitters[]; };
#ifdef DIRECTIONAL_LIGHTS
layout(binding = UNIT_PHOTON_CELLS) uniform usamplerBuffer projectionCells;
#endif
layout(std430, binding = SSBO_PHOTON_COUNTERS) buffer Counters { uint counters[]; };
layout(std430, binding = SSBO_PHOTON_STAGING) writeonly buffer Staging { Photon staging[]; };
layout(std430, binding = SSBO_PHOTON_PATHS) writeonly buffer PathCounts { uint pathCounts[]; };
layout(std430, binding = SSBO_PHOTON_EMITTED) writeonly buffer Emitted { vec4 emitted[]; };

uniform uint pathCount;
uniform int emitterCount;
uniform uint capacity;      // staging slots
uniform int maxBounces;     // surfaces a photon may reach
uniform int russianRoulette;
uniform uint firstSurfaceRoulette; // bit k: roulette at the first surface for the photons of kLight* kind k
uniform float rayEpsilon;   // scene units: how far a scattered ray starts off its surface
uniform float causticAlpha; // the roughest lobe (GGX alpha) a caustic path may bounce off (-1: none)
uniform uint seed;

int findEmitter(uint path)
{
    int lo = 0, hi = emitterCount - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (emitters[mid].range.x <= path) lo = mid; else hi = mid - 1;
    }
    return lo;
}

// Emission: origin, direction and power of path `path`, the j-th of its emitter's n (a Hammersley set:
// stratified in the first dimension, radical inverses in the others).
void emit(PhotonEmitter e, uint j, uint n, out vec3 origin, out vec3 dir, out vec3 power)
{
    vec2 u = vec2((float(j) + 0.5) / float(n), radicalInverse2(j));
    vec2 w = vec2(radicalInverse(j, 3u), radicalInverse(j, 5u));
    int kind = int(e.positionType.w);
    power = e.powerCosInner.rgb;
    origin = e.positionType.xyz;
    if (kind == kLightPoint) {
        float z = 1.0 - 2.0 * u.x, r = sqrt(max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * u.y;
        dir = vec3(r * cos(phi), r * sin(phi), z);
    } else if (kind == kLightSpot) {
        // Uniform in the outer cone; the glTF falloff weights the power (1 inside a hard cone).
        float cosOuter = e.directionCos.w;
        float z = 1.0 - u.x * (1.0 - cosOuter), r = sqrt(max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * u.y;
        vec3 t, b;
        basisAround(e.directionCos.xyz, t, b);
        dir = normalize(r * cos(phi) * t + r * sin(phi) * b + z * e.directionCos.xyz);
        power *= spotWeight(cosOuter, e.powerCosInner.w, z);
#ifdef DIRECTIONAL_LIGHTS
    } else if (kind == kLightDirectional) {
        // Uniform over the entries of the light's emission list (photon_project.comp's marked cells,
        // each cell repeated by its guided weight; PhotonTracer::guide): the stratified coordinate picks
        // the entry and the place across it, the radical inverse the place along it. A cell of k copies
        // is picked k times as often as a cell of one, so its photons carry 1 / k of the power times
        // entries / cells (v2.z): the estimate stays unbiased.
        float entries = e.v2.x, s = u.x * entries;
        uint i = min(uint(s), uint(entries) - 1u), grid = uint(e.v1.w);
        uint entry = texelFetch(projectionCells, int(uint(e.v2.y) + i)).r;
        uint cell = entry & 0xFFFFu;
        power *= e.v2.z / float(entry >> 16);
        vec2 f = (vec2(cell % grid, cell / grid) + vec2(s - float(i), u.y)) * e.v0.w;
        origin += f.x * e.v0.xyz + f.y * e.v1.xyz;
        dir = e.directionCos.xyz;
#endif
    } else {
        // One-sided emitting triangle: uniform point, cosine-weighted direction about its normal.
        float s = sqrt(w.x);
        vec3 a = e.v0.xyz, bb = e.v1.xyz, c = e.v2.xyz;
        origin = (1.0 - s) * a + s * (1.0 - w.y) * bb + s * w.y * c;
        dir = cosineDirection(e.directionCos.xyz, u);
        origin += e.directionCos.xyz * rayEpsilon;
    }
}

void main()
{
    uint path = gl_GlobalInvocationID.x;
    if (path >= pathCount) return;
    uint stored = 0u;
    if (emitterCount == 0) {
        pathCounts[path] = 0u;
        emitted[path] = vec4(0.0);
        return;
    }
    PhotonEmitter e = emitters[findEmitter(path)];
    vec3 origin, dir, power;
    emit(e, path - e.range.x, e.range.y, origin, dir, power);
    emitted[path] = vec4(power, 0.0);
    uint rng = pcgHash(path ^ pcgHash(seed));
    bool caustic = true; // every bounce so far off a near-specular lobe
    bool firstRoulette = ((firstSurfaceRoulette >> uint(e.positionType.w)) & 1u) != 0u;

    for (int bounce = 0; bounce < maxBounces; ++bounce) {
        if (max(power.r, max(power.g, power.b)) <= 0.0) break;
        Hit hit;
        if (!closestHit(origin, dir, 0.0, 3.0e38, hit)) break;
        SceneHit h = sceneHit(hit);
        vec3 p = h.p, ng = h.ng, n = h.n;
        Material m = h.m;
        BrdfParams b = h.b;
        vec3 wo = -dir;
        if (dot(ng, wo) <= 0.0) {
            if (m.flags.y == 0) break; // the back of a one-sided surface is black
            ng = -ng;
            n = -n;
        }
        if (max(m.emissionRoughness.r, max(m.emissionRoughness.g, m.emissionRoughness.b)) > 0.0) break;
        if (bounce > 0) {
            uint slot = atomicAdd(counters[kCounterStaged], 1u);
            if (slot < capacity) {
                staging[slot].positionPath = vec4(p, uintBitsToFloat(path));
                staging[slot].powerIndex = vec4(power, uintBitsToFloat(stored));
                staging[slot].incoming = vec4(wo, caustic ? 1.0 : 0.0);
                staging[slot].normal = vec4(dot(n, wo) > 0.0 ? n : ng, 0.0);
            }
            stored += 1u;
        }
        if (b.weight <= 0.0 && !brdfHasDiffuse(b)) break;
        float u1 = nextRandom(rng);
        vec2 u = vec2(nextRandom(rng), nextRandom(rng));
        vec3 wi;
        vec3 nf = dot(n, wo) > 0.0 ? n : ng;
        caustic = caustic && b.alpha <= causticAlpha && u1 < specularProbability(b, nf, wo);
        vec3 weight = scatterPhoton(b, nf, wo, u1, u, wi);
        if (dot(ng, wi) <= 0.0) break;
        vec3 next = power * weight;
        if (russianRoulette != 0 && (bounce > 0 || firstRoulette)) {
            float keep = min(1.0, max(next.r, max(next.g, next.b)) / max(power.r, max(power.g, power.b)));
            if (nextRandom(rng) >= keep) break;
            next /= keep;
        }
        power = next;
        origin = p + ng * rayEpsilon;
        dir = wi;
    }
    pathCounts[path] = stored;
}
