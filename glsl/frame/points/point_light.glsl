// The direct light at the points (common/lighting.glsl), for the point light pass and for any other point a
// gather finds (micro-rendering's ray-cast micro-pixels, point projection's hole rays). Compiled with the
// moving frame's Frame::directLightDefines in every frame: the points keep one deterministic light per frame
// (the moving form's per-kind estimators), whose lobe direction and spread the glossy points need; the
// uniforms are the direct pass's (Frame::setDirectLightUniforms). Where the scene's lights are point, spot
// and directional lights alone and the frame casts shadow rays (shadow.still=rays), their visibility is one
// ray towards the light (RAY_SHADOWS, gl/frame/points/point_cloud.cpp's pointLightDefines), not the shadow
// map: the sun's one view of all of Sponza leaked light at every contact, and micro-rendering's indirect light
// on a white Lambertian copy of assets/setups/sponza-sun.json read 1.132, 1.077 and 1.052 of the path
// tracer's with maps of 256^2, 1024^2 (the default) and 4096^2 texels, 1.047 with the rays
// (gl/technique/microrender/README.md). Emitting triangles keep the moving form's cube from the centroid.
#ifndef BOUNCE_POINT_LIGHT_GLSL
#define BOUNCE_POINT_LIGHT_GLSL

#include "common/lighting.glsl"

// The lights' direct light at a surface point p (normal n) for the points: the outgoing radiance of the
// BRDF's diffuse lobe alone (micro-rendering §2.2: "when using only diffuse surfaces, we can store the
// reflected radiance inside the point hierarchy"), and for the glossy lobe, which depends on where it is
// seen from, the shadowed irradiance with the luminance-weighted mean of the directions it comes from
// (point_cloud.glsl's `glossy`).
// The diffuse lobe is core/brdf.h's, (1 - w Fo)(1 - w Fi) c_diff / pi: what the glossy interface lets
// through on the way in, 1 - w F(n.wi) per light, and on the way out, 1 - w F(n.wo). One radiance per point
// cannot follow wo, so it takes the mean of 1 - w F(n.wo) over the outgoing directions weighted by their
// cosine (the flux it sends): 1 - w (F0 + (1 - F0) / 21), as 2 int_0^1 (1 - mu)^5 mu dmu = 1/21.
// Without both factors a dielectric of Sponza's (w = 1, F0 = 0.04) sent 14% more light than its BRDF
// lets through: micro-rendering's indirect light on assets/setups/sponza-sun.json read 1.19 of the path tracer's
// `onebounce` minus `direct`, and 1.05 with every material Lambertian (gl/technique/microrender/README.md).
struct PointLight {
    vec3 radiance;   // (1 - w Fo) (1 - w Fi) (c_diff / pi) E, Fo the cosine-weighted mean (above)
    vec3 irradiance; // E, shadowed
    vec3 direction;  // unit; n where no light arrives
    float spread2;   // the mean squared angle between `direction` and the directions light comes from (rad^2)
};

// The sums over the lights, weighted by the luminance w_i of the shadowed irradiance each brings.
struct PointLightSums {
    float weight;     // sum w_i
    vec3 direction;   // sum w_i wi
    float extent2;    // sum w_i m_i, m_i the light's own mean squared angle about its centre (0: punctual)
};

// Whether unshadowed irradiance from direction wi reaches a point of normal n at all (else its shadow lookup
// is skipped).
bool pointLightArrives(vec3 irradiance, vec3 n, vec3 wi)
{
    return max(irradiance.r, max(irradiance.g, irradiance.b)) > 0.0 && dot(n, wi) > 0.0;
}

// One light's share: shadowed irradiance e from direction wi; m the light's mean squared angle.
void addPointLight(inout PointLight pl, inout PointLightSums sums, vec3 diffuse, vec3 wi, vec3 e, float m)
{
    pl.radiance += diffuse * (1.0 / kPi) * e;
    pl.irradiance += e;
    float w = dot(e, kLuminance);
    sums.weight += w;
    sums.direction += wi * w;
    sums.extent2 += m * w;
}

// An emitting triangle's mean squared angle about its centroid seen from p, as a disc's of the same solid
// angle Omega = A cos / d^2: a disc of angular radius theta has theta^2 / 2 = Omega / (2 pi).
float areaTriangleExtent2(Light l, vec3 p, vec3 wi)
{
    int first = l.shadow.z;
    vec3 a = lightPolygon(first), b = lightPolygon(first + 1), c = lightPolygon(first + 2);
    vec3 d = (a + b + c) / 3.0 - p;
    float area = 0.5 * length(cross(b - a, c - a));
    return area * abs(dot(wi, l.direction)) / max(dot(d, d), 1e-12) / (2.0 * kPi);
}

// b: the surface's BRDF (its diffuse colour, F0 and w; alpha is not read).
PointLight pointDirectLight(vec3 p, vec3 n, BrdfParams b)
{
    PointLight pl = PointLight(vec3(0.0), vec3(0.0), n, 0.0);
    PointLightSums sums = PointLightSums(0.0, vec3(0.0), 0.0);
    vec3 wi;
#ifdef PUNCTUAL_LIGHTS
    for (int i = 0; i < punctualLightCount; ++i) {
        vec3 e = punctualIrradiance(frameLight(i), p, n, wi);
        if (pointLightArrives(e, n, wi))
            addPointLight(pl, sums, b.diffuse * brdfTransmission(b, dot(n, wi)), wi,
                          e * shadowVisibility(frameLight(i), p, n), 0.0);
    }
#endif
#ifdef AREA_LIGHTS
    for (int i = punctualLightCount; i < lightCount; ++i) {
        vec3 e = areaTriangleIrradiance(frameLight(i), p, n, wi);
        if (pointLightArrives(e, n, wi))
            addPointLight(pl, sums, b.diffuse * brdfTransmission(b, dot(n, wi)), wi,
                          e * areaTriangleVisibility(frameLight(i), p, n), areaTriangleExtent2(frameLight(i), p, wi));
    }
#endif
    pl.radiance *= brdfMeanTransmission(b);
    if (sums.weight > 0.0) {
        pl.direction = normalize(sums.direction);
        // Each light's own extent, and how far the lights' directions lie from their mean (for unit vectors,
        // sum w_i |wi - mean|^2 = W - |sum w_i wi|^2 / W, the squared angle for small angles).
        float apart = max(sums.weight - dot(sums.direction, sums.direction) / sums.weight, 0.0);
        pl.spread2 = (sums.extent2 + apart) / sums.weight;
    }
    return pl;
}

// The GGX alpha of a lobe that sends light arriving with mean squared angle `spread2` about one direction:
// the lobe widened by the light's extent, which one direction does not have. The slope distributions'
// variances add: GGX's core has the slope variance of Beckmann's, alpha^2 / 2 per axis, and directions
// spread by m (both axes) about the light's are spread by m / 4 in the half vector, a slope variance of
// m / 8 per axis, so alpha'^2 = alpha^2 + m / 4 (a disc of angular radius theta: alpha^2 + theta^2 / 8).
// cornell-glossy's emitter seen from the metal block's top: alpha 0.09 becomes 0.11 to 0.13. The lobe
// keeps its energy. Against a numerical integral over the emitter of what the middle of the top sends
// towards six points of the ceiling and the red wall, the widened lobe was 5-10% off where the lobe is
// strong (about the centroid alone: 26-44% low) and up to 65% high in its tail, at a fifth of the peak.
float widenedAlpha(float alpha, float spread2) { return sqrt(alpha * alpha + spread2 / 4.0); }

// A Lambertian point's outgoing radiance, (c_diff / pi) E (scenes without a glossy lobe, w = 0 everywhere:
// without GLOSSY_POINTS): for micro-rendering's ray-cast micro-pixels too.
vec3 pointDirectRadiance(vec3 p, vec3 n, vec3 diffuse)
{
    if (max(diffuse.r, max(diffuse.g, diffuse.b)) <= 0.0) return vec3(0.0);
    return pointDirectLight(p, n, BrdfParams(diffuse, vec3(0.0), 0.0, 1.0)).radiance;
}

// Outgoing radiance towards wo of a surface point with the BRDF b, every lobe (a ray's hit on a glossy
// surface, seen from the gather sample): the frame's estimator, as a pixel there would get it.
vec3 surfaceDirectRadiance(vec3 p, vec3 n, vec3 wo, BrdfParams b)
{
    vec3 radiance = vec3(0.0);
    addDirectLight(radiance, p, n, wo, b, vec2(0.0)); // the moving form: no rotation
    return radiance;
}

#endif
