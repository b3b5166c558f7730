// Direct light from one light at a surface point: the BRDF times the irradiance it receives, shadowed.
#ifndef BOUNCE_LIGHTING_GLSL
#define BOUNCE_LIGHTING_GLSL

#include "common/brdf.glsl"
#include "common/scene.glsl"
#include "common/shadow.glsl"

// Irradiance at p (normal n) from a Lambertian emitting triangle of radiance L, by Lambert's formula for
// the polygon clipped to p's upper hemisphere: E = L/2 sum_i Theta_i (n . Gamma_i). Exact, unshadowed.
float polygonFormFactor(vec3 p, vec3 n, vec3 a, vec3 b, vec3 c)
{
    vec3 v[3] = vec3[3](a - p, b - p, c - p);
    vec3 clipped[4];
    int count = 0;
    for (int i = 0; i < 3; ++i) {
        vec3 cur = v[i], nxt = v[(i + 1) % 3];
        float dc = dot(cur, n), dn = dot(nxt, n);
        if (dc >= 0.0) clipped[count++] = cur;
        if ((dc >= 0.0) != (dn >= 0.0)) clipped[count++] = cur + (nxt - cur) * (dc / (dc - dn));
    }
    if (count < 3) return 0.0;
    float sum = 0.0;
    for (int i = 0; i < count; ++i) {
        vec3 r0 = normalize(clipped[i]), r1 = normalize(clipped[(i + 1) % count]);
        vec3 g = cross(r0, r1);
        float len = length(g);
        if (len > 1e-9) sum += acos(clamp(dot(r0, r1), -1.0, 1.0)) * dot(n, g / len);
    }
    return abs(sum) / (2.0 * kPi);
}

// Outgoing radiance towards wo from light l at p. For area lights the diffuse part is exact (polygon
// form factor); the glossy part evaluates the BRDF towards the triangle's centroid (an approximation).
vec3 directFromLight(Light l, vec3 p, vec3 n, vec3 wo, BrdfParams b)
{
    int type = int(l.positionType.w);
    vec3 wi;
    vec3 irradiance;
    if (type == kLightDirectional) {
        wi = -l.directionCosOuter.xyz;
        irradiance = l.intensityCosInner.rgb * max(dot(n, wi), 0.0);
    } else if (type == kLightArea) {
        int first = l.shadow.z;
        vec3 a = lightPolygons[first].xyz, bb = lightPolygons[first + 1].xyz, c = lightPolygons[first + 2].xyz;
        vec3 emitterNormal = l.directionCosOuter.xyz;
        if (dot(p - a, emitterNormal) <= 0.0) return vec3(0.0); // behind the one-sided emitter
        wi = normalize((a + bb + c) / 3.0 - p);
        irradiance = l.intensityCosInner.rgb * kPi * polygonFormFactor(p, n, a, bb, c);
    } else {
        vec3 d = l.positionType.xyz - p;
        float d2 = max(dot(d, d), 1e-12);
        wi = d * inversesqrt(d2);
        float w = type == kLightSpot ? spotWeight(l, dot(-wi, l.directionCosOuter.xyz)) : 1.0;
        irradiance = l.intensityCosInner.rgb * (w * max(dot(n, wi), 0.0) / d2);
    }
    if (max(irradiance.r, max(irradiance.g, irradiance.b)) <= 0.0) return vec3(0.0);
    // A point on the light-facing side must see the light; both cosines are checked by brdfEval.
    return brdfEval(b, n, wo, wi) * irradiance * shadowVisibility(l, p, n);
}

#endif
