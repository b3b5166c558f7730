// The frame's direct light at a surface point: one estimator per kind of light, and addDirectLight (at the
// end), the one loop over the scene's lights that every pass shading a point with them calls.
#ifndef BOUNCE_LIGHTING_GLSL
#define BOUNCE_LIGHTING_GLSL

#include "common/brdf.glsl"
#include "common/scene.glsl"
#include "common/shadow.glsl"

// The scene's lights in their order (gl/frame/frame_lights.h): [0, punctualLightCount) point, spot and
// directional lights, [punctualLightCount, lightCount) emitting triangles. Frame::setDirectLightUniforms.
uniform int punctualLightCount;
uniform int lightCount;

// Irradiance at p (normal n) from a Lambertian emitting triangle of radiance L, by Lambert's formula for
// the polygon clipped to p's upper hemisphere: E = L/2 sum_i Theta_i (n . Gamma_i). Exact, unshadowed.
// `toward`: the clipped polygon's vertex mean, from p (above p's horizon wherever the result is not 0).
float polygonFormFactor(vec3 p, vec3 n, vec3 a, vec3 b, vec3 c, out vec3 toward)
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
    toward = n;
    if (count < 3) return 0.0;
    toward = vec3(0.0);
    for (int i = 0; i < count; ++i) toward += clipped[i];
    float sum = 0.0;
    for (int i = 0; i < count; ++i) {
        vec3 r0 = normalize(clipped[i]), r1 = normalize(clipped[(i + 1) % count]);
        vec3 g = cross(r0, r1);
        float len = length(g);
        if (len > 1e-9) sum += acos(clamp(dot(r0, r1), -1.0, 1.0)) * dot(n, g / len);
    }
    return abs(sum) / (2.0 * kPi);
}

// Irradiance at p (normal n) from a point, spot or directional light l, unshadowed, and the direction
// wi towards the light. Shared by the direct pass and by techniques that light other points (atlases).
vec3 punctualIrradiance(Light l, vec3 p, vec3 n, out vec3 wi)
{
    if (l.type == kLightDirectional) {
        wi = -l.direction;
        return l.intensity * max(dot(n, wi), 0.0);
    }
    vec3 d = l.position - p;
    float d2 = max(dot(d, d), 1e-12);
    wi = d * inversesqrt(d2);
    float w = l.type == kLightSpot ? spotWeight(l, dot(-wi, l.direction)) : 1.0;
    return l.intensity * (w * max(dot(n, wi), 0.0) / d2);
}

// Outgoing radiance towards wo from a point, spot or directional light l at p.
//
// Callers loop over the lights of each kind separately (gl/frame/gpu_scene.h keeps the punctual lights
// first, the emitting triangles after them) instead of switching on the kind per light: a SIMD
// rasteriser such as llvmpipe runs both sides of a branch whenever any lane needs either, and the polygon
// form factor below is heavy, so a per-light switch made every spot-lit pixel pay for it (2.5x slower).
vec3 directFromPunctual(Light l, vec3 p, vec3 n, vec3 wo, BrdfParams b)
{
    vec3 wi;
    vec3 irradiance = punctualIrradiance(l, p, n, wi);
    if (max(irradiance.r, max(irradiance.g, irradiance.b)) <= 0.0) return vec3(0.0);
    // The BRDF checks both cosines; a point on the light-facing side must see the light.
    return brdfEval(b, n, wo, wi) * irradiance * shadowVisibility(l, p, n);
}

// Irradiance at p (normal n) from one emitting triangle l, unshadowed and exact (polygon form factor), and
// the direction wi towards the centre of its part above p's horizon, which stands for the triangle where a
// BRDF is evaluated. (Towards the whole triangle's centroid, a triangle that straddles the horizon with its
// centroid below it lost its visible part: the BRDF is 0 below the horizon. On cornell-area the tall
// block's face toward the emitter read 11% under the path tracer, issue 58.)
vec3 areaTriangleIrradiance(Light l, vec3 p, vec3 n, out vec3 wi)
{
    int first = l.shadow.z;
    vec3 a = lightPolygon(first), bb = lightPolygon(first + 1), c = lightPolygon(first + 2);
    wi = normalize((a + bb + c) / 3.0 - p);
    if (dot(p - a, l.direction) <= 0.0) return vec3(0.0); // behind the one-sided emitter
    vec3 toward;
    float formFactor = polygonFormFactor(p, n, a, bb, c, toward);
    if (formFactor > 0.0) wi = normalize(toward);
    return l.intensity * kPi * formFactor;
}

// The moving frame's visibility of emitting triangle l from p: its mesh's shadow cube, seen from the mesh's
// centroid, filtered by PCF, or by PCSS (SHADOW_PCSS) for a penumbra as wide as the emitter.
float areaTriangleVisibility(Light l, vec3 p, vec3 n)
{
#ifdef SHADOW_PCSS
    int first = l.shadow.z;
    vec3 a = lightPolygon(first), bb = lightPolygon(first + 1), c = lightPolygon(first + 2);
    // The side of the square this triangle is half of: the emitter's width PCSS assumes.
    float width = sqrt(length(cross(bb - a, c - a)));
    return pcssVisibility(l, p, n, width);
#else
    return shadowVisibility(l, p, n);
#endif
}

// Outgoing radiance towards wo from one emitting triangle l at p. The diffuse part is exact (polygon
// form factor); the glossy part evaluates the BRDF towards the triangle's centroid (an approximation).
vec3 directFromAreaTriangle(Light l, vec3 p, vec3 n, vec3 wo, BrdfParams b)
{
    vec3 wi;
    vec3 irradiance = areaTriangleIrradiance(l, p, n, wi);
    if (max(irradiance.r, max(irradiance.g, irradiance.b)) <= 0.0) return vec3(0.0);
    return brdfEval(b, n, wo, wi) * irradiance * areaTriangleVisibility(l, p, n);
}

// Still frames (gl/frame/shadow_maps.h): one emitting triangle's outgoing radiance towards wo from this
// frame's point x on its mesh (the light's position; the mesh's area A in its sampleArea on the
// triangle that holds x, 0 on the others), before the visibility V of the mesh's shadow cube at x, which
// the caller applies once per mesh (glsl/frame/direct.frag).
//   diffuse  the one-sample estimate L A cos_p cos_x / r^2 V f_diffuse: unbiased, and never negative, so
//            the still frames' mean is the path tracer's soft shadow;
//   glossy   the lobe over kAreaGlossyPoints^2 stratified points of the triangle (rotated from frame to
//            frame by `rotation`) times V: a metal's lobe narrower than the emitter is what one point per
//            frame cannot average (fireflies for hundreds of frames). The frames' mean is the unshadowed
//            lobe times the share of the emitter's area that p sees, which differs from the path tracer's
//            only where the emitter is partly hidden from a glossy surface.
// A ratio estimator (the unshadowed light times the visible share weighted by what each point sends, summed
// over the frames) was measured too: on the soft-shadow closed form (tests/gl/still_frames_test.cpp) its
// largest difference after 64 frames was 7.9% against 3.8% for the one-sample estimate, since the frames'
// mean keeps the early frames' ratios.
const int kAreaGlossyPoints = 4;

// The glossy lobe's light from emitting triangle l at p (in front of it), unshadowed, over the triangle's
// kAreaGlossyPoints^2 stratified points rotated by `rotation`: 0 in a scene without a lobe.
vec3 areaGlossyUnshadowed(Light l, vec3 p, vec3 n, vec3 wo, BrdfParams b, vec2 rotation)
{
    vec3 glossy = vec3(0.0);
#ifndef SCENE_DIFFUSE_ONLY
    int first = l.shadow.z;
    vec3 a = lightPolygon(first), bb = lightPolygon(first + 1), c = lightPolygon(first + 2);
    vec3 emitterNormal = l.direction;
    float area = 0.5 * length(cross(bb - a, c - a));
    const float m = float(kAreaGlossyPoints);
    for (int j = 0; j < kAreaGlossyPoints; ++j)
        for (int i = 0; i < kAreaGlossyPoints; ++i) {
            vec2 u = fract((vec2(i, j) + 0.5) / m + rotation);
            float su = sqrt(u.x); // uniform over the triangle
            vec3 x = a * (1.0 - su) + bb * (su * (1.0 - u.y)) + c * (su * u.y);
            vec3 d = x - p;
            float d2 = max(dot(d, d), 1e-12);
            vec3 wi = d * inversesqrt(d2);
            float g = max(-dot(wi, emitterNormal), 0.0) * max(dot(n, wi), 0.0) / d2;
            glossy += brdfGlossy(b, n, wo, wi) * (g * area / (m * m));
        }
    glossy *= l.intensity;
#endif
    return glossy;
}

// Still frames: the geometric term cos_x cos_p / r^2 between p (normal n) and this frame's point on emitting
// triangle l's mesh (its position), and the direction wi towards that point.
float areaSampleGeometry(Light l, vec3 p, vec3 n, out vec3 wi)
{
    vec3 d = l.position - p;
    float d2 = max(dot(d, d), 1e-12);
    wi = d * inversesqrt(d2);
    return max(-dot(wi, l.direction), 0.0) * max(dot(n, wi), 0.0) / d2;
}

// Still frames: emitting triangle l's light towards wo from this frame's point on its mesh, diffuse and
// glossy as described above, before the mesh's visibility.
vec3 areaSampleUnshadowed(Light l, vec3 p, vec3 n, vec3 wo, BrdfParams b, vec2 rotation)
{
    float sampleArea = l.sampleArea;
#ifdef SCENE_DIFFUSE_ONLY
    if (sampleArea <= 0.0) return vec3(0.0);
#endif
    int first = l.shadow.z;
    vec3 a = lightPolygon(first);
    vec3 emitterNormal = l.direction;
    if (dot(p - a, emitterNormal) <= 0.0) return vec3(0.0); // behind the one-sided emitter
    vec3 L = l.intensity;
    vec3 glossy = areaGlossyUnshadowed(l, p, n, wo, b, rotation);
    vec3 diffuse = vec3(0.0);
    if (sampleArea > 0.0) {
        vec3 wi;
        float g = areaSampleGeometry(l, p, n, wi);
        vec3 diffuseFactor, glossyLobe;
        brdfEvalLobes(b, n, wo, wi, diffuseFactor, glossyLobe);
        diffuse = diffuseFactor * b.diffuse * L * (g * sampleArea);
    }
    return diffuse + glossy;
}

// Still frames: the light of the emitting triangles [first, end) towards wo from this frame's point on
// each mesh (areaSampleUnshadowed). The triangles of one mesh are consecutive and share its shadow cube
// (shadow.x, its first layer): their light is summed and the cube read once per mesh.
vec3 sampledAreaLights(int first, int end, vec3 p, vec3 n, vec3 wo, BrdfParams b, vec2 rotation)
{
    vec3 sum = vec3(0.0), mesh = vec3(0.0);
    for (int i = first; i < end; ++i) {
        Light l = frameLight(i);
        mesh += areaSampleUnshadowed(l, p, n, wo, b, rotation);
        if (i + 1 < end && frameLight(i + 1).shadow.x == l.shadow.x) continue;
        if (max(mesh.r, max(mesh.g, mesh.b)) > 0.0) sum += mesh * shadowVisibility(l, p, n);
        mesh = vec3(0.0);
    }
    return sum;
}

#ifdef AREA_RATIO
// Moving frames with temporal reuse of the direct light (`temporal.direct`; gl/frame/README.md, "The area
// lights' ratio estimator"): Heitz, Hill and McGuire, "Combining Analytic Direct Illumination and Stochastic
// Shadows" (I3D 2018). The emitting triangles' light is the exact unshadowed light (the polygon form
// factor, the lobe towards each centroid, as in moving frames) times the share of it that reaches p, and
// only that share is estimated stochastically: this frame's point x on each mesh (the still frames'
// sample) with weight w = lum(L) cos_x cos_p A / r^2, its one-sample estimate of the mesh's unshadowed
// light, and x's visibility V (a shadow ray, or the cube moved to x). The pass writes the sums of w V and
// of w over the meshes; the temporal reuse averages both over the frames and the frame divides the two
// (Frame::resolveAreaRatio), a ratio of sums, so that E[w V] / E[w] is the visible share of the mesh's
// light: unshadowed pixels take the exact light in every frame, noise is left only in penumbrae.
void areaLightsRatio(int first, int end, vec3 p, vec3 n, vec3 wo, BrdfParams b, out vec3 unshadowed,
                     out vec2 visibility)
{
    unshadowed = vec3(0.0);
    visibility = vec2(0.0);
    float meshWeight = 0.0;
    for (int i = first; i < end; ++i) {
        Light l = frameLight(i);
        vec3 wi;
        vec3 irradiance = areaTriangleIrradiance(l, p, n, wi);
        if (max(irradiance.r, max(irradiance.g, irradiance.b)) > 0.0) unshadowed += brdfEval(b, n, wo, wi) * irradiance;
        if (l.sampleArea > 0.0 && dot(p - lightPolygon(l.shadow.z), l.direction) > 0.0) {
            vec3 wx;
            float g = areaSampleGeometry(l, p, n, wx);
            meshWeight += dot(l.intensity, vec3(0.2126, 0.7152, 0.0722)) * g * l.sampleArea;
        }
        if (i + 1 < end && frameLight(i + 1).shadow.x == l.shadow.x) continue;
        if (meshWeight > 0.0) visibility += meshWeight * vec2(shadowVisibility(l, p, n), 1.0);
        meshWeight = 0.0;
    }
}
#endif

// The frame's direct light at surface point p (normal n, BRDF b) towards wo, added to `radiance` light by
// light in the lights' order (so that a pixel's emission, added first, keeps its place in the sum):
//   point, spot, directional  directFromPunctual, through the shadow maps (PCF in moving frames, one shifted
//                             tap in still frames: Frame::setDirectLightUniforms);
//   emitting triangles        moving frames: directFromAreaTriangle, the diffuse part exact and the lobe towards
//                             the centroid, shadowed from the mesh's cube (PCSS with SHADOW_PCSS); still
//                             frames (AREA_SAMPLED): sampledAreaLights, this frame's point on each mesh and the
//                             lobe over the triangles' points rotated by `rotation`, unbiased over the frames.
// The one estimator of every pass that lights a point with the scene's lights: the G-buffer's pixels
// (frame/direct.frag), the point methods' ray hits (frame/points/point_light.glsl), photon mapping's gather
// hits (technique/photon/photon_gather.glsl). Frame::directLightDefines gives the defines that choose the
// form (PUNCTUAL_LIGHTS, AREA_LIGHTS: the kinds the scene has; AREA_SAMPLED, SHADOW_CASCADES, SHADOW_PCSS:
// the still or the moving frame's form), so that a pixel and a ray hit at the same point get the same light
// (tests/gl/direct_estimator_test.cpp).
void addDirectLight(inout vec3 radiance, vec3 p, vec3 n, vec3 wo, BrdfParams b, vec2 rotation)
{
#ifdef PUNCTUAL_LIGHTS
    for (int i = 0; i < punctualLightCount; ++i) radiance += directFromPunctual(frameLight(i), p, n, wo, b);
#endif
#if defined(AREA_LIGHTS) && !defined(AREA_RATIO) // AREA_RATIO: frame/direct.frag adds them (areaLightsRatio)
#ifdef AREA_SAMPLED
    radiance += sampledAreaLights(punctualLightCount, lightCount, p, n, wo, b, rotation);
#else
    for (int i = punctualLightCount; i < lightCount; ++i) radiance += directFromAreaTriangle(frameLight(i), p, n, wo, b);
#endif
#endif
}

#endif
