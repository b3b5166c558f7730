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
#include "technique/photon/cut_lookup.glsl"
#include "technique/photon/density.glsl"

layout(binding = UNIT_BASE_COLOR) uniform sampler2DArray baseColorTextures;

uniform int punctualLightCount; // lights [0, punctualLightCount): point, spot, directional
uniform int lightCount;         // lights [punctualLightCount, lightCount): emitting triangles

// Radiance leaving the hit of a ray from `origin` along `dir` back towards the origin: direct light
// (shadow maps) plus photon-map indirect light; emission is left out (the frame's direct light has it).
// coverage as CutLookup's (2 with DENSITY_PHOTONS).
vec3 gatherRadiance(vec3 origin, vec3 dir, Hit hit, out int coverage)
{
    coverage = 2;
    uint tri = hit.triangle;
    vec3 p0 = sceneVertexPosition(sceneVertexIndex(tri, 0));
    vec3 p1 = sceneVertexPosition(sceneVertexIndex(tri, 1));
    vec3 p2 = sceneVertexPosition(sceneVertexIndex(tri, 2));
    vec3 y = (1.0 - hit.b.x - hit.b.y) * p0 + hit.b.x * p1 + hit.b.y * p2;
    vec3 ng = normalize(cross(p1 - p0, p2 - p0));
    vec3 n = sceneTriangleNormal(tri, hit.b);
    Material m = materials[sceneTriangleMaterial(tri)];
    vec3 wo = -dir;
    if (dot(ng, wo) <= 0.0) {
        if (m.flags.y == 0) return vec3(0.0); // the back of a one-sided surface is black
        ng = -ng;
        n = -n;
    }
    if (dot(n, wo) <= 0.0) n = ng;
    vec3 baseColor = m.baseColorMetallic.rgb;
    if (m.flags.x >= 0) {
        vec2 uv = sceneTriangleUv(tri, hit.b);
        baseColor *= textureLod(baseColorTextures, vec3(uv, float(m.flags.x)), 0.0).rgb;
    }
    BrdfParams b = brdfParams(baseColor, m.baseColorMetallic.a, m.emissionRoughness.a, m.specularColorSpecular.a,
                              m.specularColorSpecular.rgb);
    vec3 radiance = vec3(0.0);
#ifdef PUNCTUAL_LIGHTS
    for (int l = 0; l < punctualLightCount; ++l) radiance += directFromPunctual(lights[l], y, n, wo, b);
#endif
#ifdef AREA_LIGHTS
    for (int l = punctualLightCount; l < lightCount; ++l) radiance += directFromAreaTriangle(lights[l], y, n, wo, b);
#endif
#ifdef DENSITY_PHOTONS
    float radius;
    PhotonNode root = photonNodes[1];
    DensitySums s = nearestPhotons(y, n, nearestStartRadius(root), radius);
    vec3 irradiance = s.power / (kPi * radius * radius);
    vec3 wi = n;
#else
    CutLookup c = cutIrradiance(y, n);
    coverage = c.coverage;
    vec3 irradiance = c.irradiance;
    vec3 wi = dot(c.incoming, n) > 0.0 ? c.incoming : n;
#endif
    // The photons' irradiance reflected as from one direction, their mean: exact for the Lambertian part.
    return radiance + brdfEval(b, n, wo, wi) * irradiance;
}

#endif
