// Shadow-map visibility for every light type: all shadow views live in one depth array (a spot uses one
// perspective layer, a point light or an area light six cube-face layers, a directional light one
// orthographic layer). Hardware depth comparison; PCF over a (2r+1)^2 kernel, r = pcfRadius (pcfNearest: the
// taps unfiltered), set on every program that includes this file (ShadowMaps::setPcfUniforms).
#ifndef BOUNCE_SHADOW_GLSL
#define BOUNCE_SHADOW_GLSL

#include "common/scene.glsl"
#ifdef RAY_SHADOWS
#include "common/raycast.glsl"
#endif

layout(binding = UNIT_SHADOW_MAPS) uniform sampler2DArrayShadow shadowMaps;
uniform int pcfRadius;
uniform int pcfNearest; // 1: nearest taps (shadow.linear off); 0, the default: 2x2 bilinear comparisons
// The receiver's offset along its normal, in texels at its distance (ShadowMaps::setPcfUniforms): 1.5 for
// filtered taps, less in still frames, whose jittered nearest taps need no margin for a filter's footprint
// and whose mean would keep the offset's shift of every contact shadow.
uniform float shadowNormalOffset = 1.5;

// Percentage-closer filtering over (2r+1)^2 taps one texel apart around uv, each a 2x2 bilinear comparison
// (or the nearest texel's), computed from (r+1)^2 textureGather calls instead of (2r+1)^2 filtered
// lookups: the taps together cover (2r+2)^2 texels, whose comparisons are weighted per axis 1 - f for the
// first, f for the last and 1 between (f: uv's bilinear fraction; for nearest taps f rounded to 0 or 1).
// The same sum as the taps', at 4 gathers instead of 9 lookups for r = 1 (a software rasteriser filters
// every lookup lane by lane).
float percentageCloser(vec2 uv, float layer, float ref)
{
#ifdef SHADOW_PCF_TAPS
    // The direct way, for the test that the gathers sum the same (tests/gl/shadow_pcf_test.cpp): (2r+1)^2
    // lookups, each filtered by the texture's own filter (linear or nearest) and compared by the hardware.
    vec2 texel = 1.0 / vec2(textureSize(shadowMaps, 0).xy);
    float tapSum = 0.0;
    for (int y = -pcfRadius; y <= pcfRadius; ++y)
        for (int x = -pcfRadius; x <= pcfRadius; ++x)
            tapSum += texture(shadowMaps, vec4(uv + vec2(x, y) * texel, layer, ref));
    return tapSum / float((2 * pcfRadius + 1) * (2 * pcfRadius + 1));
#endif
    vec2 size = vec2(textureSize(shadowMaps, 0).xy);
    vec2 st = uv * size - 0.5;
    vec2 base = floor(st);
    vec2 f = st - base;
    if (pcfNearest != 0) f = step(0.5, f);
    float sum = 0.0;
    for (int j = 0; j <= pcfRadius; ++j) {
        float wy0 = j == 0 ? 1.0 - f.y : 1.0, wy1 = j == pcfRadius ? f.y : 1.0;
        for (int i = 0; i <= pcfRadius; ++i) {
            float wx0 = i == 0 ? 1.0 - f.x : 1.0, wx1 = i == pcfRadius ? f.x : 1.0;
            // The 2x2 texels from base + (2i - r, 2j - r): gather at the point between them.
            vec2 c = (base + vec2(2 * i - pcfRadius, 2 * j - pcfRadius) + 1.0) / size;
            vec4 g = textureGather(shadowMaps, vec3(c, layer), ref); // (x0 y1), (x1 y1), (x1 y0), (x0 y0)
            sum += wy0 * (wx0 * g.w + wx1 * g.z) + wy1 * (wx0 * g.x + wx1 * g.y);
        }
    }
    float taps = float((2 * pcfRadius + 1) * (2 * pcfRadius + 1));
    return sum / taps;
}

// Where p (normal n) falls in shadow layer `layer`: xy the map coordinates, z the reference depth, w 0 when
// p is beyond the view (behind a perspective view's origin or past its far plane).
vec4 shadowCoordinates(int layer, vec3 p, vec3 n)
{
    ShadowView v = shadowView(layer);
    // Normal offset by shadowNormalOffset texels at the receiver's distance, so that lit surfaces do not
    // shadow themselves at grazing angles; the constant bias below covers the rest.
    float dist = v.originFar.w > 0.0 ? length(p - v.originFar.xyz) : 1.0;
    vec3 q = p + n * (shadowNormalOffset * v.texelWorld.x * dist);
    vec4 c = v.viewProj * vec4(q, 1.0);
    vec3 s = c.xyz / c.w * 0.5 + 0.5;
    return vec4(s.xy, s.z - 2e-5, c.w <= 0.0 || s.z > 1.0 ? 0.0 : 1.0);
}

#ifdef SHADOW_PCSS
// Percentage-closer soft shadows (Fernando 2005) for an emitter of side `lightWidth` whose shadow cube sits
// at its centroid: the moving frame's estimate of a penumbra (still frames sample the emitter instead).
// The blockers' mean distance from a 4x4 search over the map where the emitter's extent, seen from p,
// reaches; the penumbra's width w (d_receiver - d_blocker) / d_blocker; PCF over 5x5 comparisons that
// span it. A cube face's uv spans 2 d at distance d along its axis.
layout(binding = UNIT_SHADOW_DEPTHS) uniform sampler2DArray shadowDepths;

float shadowLinearDepth(float windowDepth, float far)
{
    float near = max(far * 1e-4, 1e-5); // gl/frame/light_views.cpp: lightNearFar
    return 2.0 * near * far / (far + near - (2.0 * windowDepth - 1.0) * (far - near));
}

float shadowWindowDepth(float linearDepth, float far)
{
    float near = max(far * 1e-4, 1e-5);
    return 0.5 * ((far + near) / (far - near) - 2.0 * far * near / ((far - near) * linearDepth)) + 0.5;
}

// The world direction of cube face `face`'s ray through uv, of unit length along the face's axis
// (glsl/common/scene.glsl's cubeFace() order, gl/frame/light_views.cpp's cubeViews and glm::lookAt).
vec3 cubeFaceRay(int face, vec2 uv)
{
    const vec3 axes[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1),
                                 vec3(0, 0, -1));
    const vec3 ups[6] = vec3[6](vec3(0, -1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1), vec3(0, -1, 0),
                                vec3(0, -1, 0));
    vec3 f = axes[face];
    vec3 r = normalize(cross(f, ups[face]));
    vec3 u = cross(r, f);
    vec2 ndc = uv * 2.0 - 1.0;
    return f + ndc.x * r + ndc.y * u;
}

// The depth along the face's axis at which `ray` meets the plane through p with normal n: what a tap
// compares against, so that a receiver at a slant does not shadow itself.
float receiverPlaneDepth(vec3 ray, vec3 origin, vec3 p, vec3 n, float fallback)
{
    float dn = dot(n, ray);
    float t = abs(dn) > 1e-6 ? dot(n, p - origin) / dn : -1.0;
    return t > 0.0 ? t : fallback;
}

float pcssVisibility(Light l, vec3 p, vec3 n, float lightWidth)
{
    if (l.shadow.x < 0) return 1.0;
    int face = cubeFace(p - l.position);
    int layer = l.shadow.x + face;
    vec4 s = shadowCoordinates(layer, p, n);
    if (s.w == 0.0) return 1.0;
    vec3 origin = shadowView(layer).originFar.xyz;
    float far = shadowView(layer).originFar.w;
    float receiver = shadowLinearDepth(s.z, far);
    float texel = 1.0 / float(textureSize(shadowMaps, 0).x);
    const float bias = 1.0 - 2e-3; // relative: the map's depth quantisation and the plane's fit
    // Taps whose rays leave the one-sided emitter backwards (into the ceiling it hangs from) carry no light
    // and see that surface at once: they are left out of both the search and the filter.
    vec3 emitterNormal = l.direction;
    // Blockers between a quarter of the way and p: their offsets from p's line reach w (d - t) / (4 t d).
    float search = clamp(0.75 * lightWidth / receiver, texel, 0.25);
    float blockers = 0.0, count = 0.0;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            vec2 uv = clamp(s.xy + (vec2(i, j) / 1.5 - 1.0) * search, vec2(0.0), vec2(1.0));
            vec3 ray = cubeFaceRay(face, uv);
            if (dot(ray, emitterNormal) <= 0.0) continue;
            float d = shadowLinearDepth(texture(shadowDepths, vec3(uv, float(layer))).r, far);
            if (d < receiverPlaneDepth(ray, origin, p, n, receiver) * bias) {
                blockers += d;
                count += 1.0;
            }
        }
    if (count == 0.0) return 1.0;
    float blocker = blockers / count;
    float radius = max(lightWidth * (receiver - blocker) / blocker / (4.0 * receiver), texel);
    float sum = 0.0, taps = 0.0;
    for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i) {
            vec2 uv = clamp(s.xy + vec2(i, j) * (radius / 2.0), vec2(0.0), vec2(1.0));
            vec3 ray = cubeFaceRay(face, uv);
            if (dot(ray, emitterNormal) <= 0.0) continue;
            float ref = shadowWindowDepth(receiverPlaneDepth(ray, origin, p, n, receiver) * bias, far);
            sum += texture(shadowMaps, vec4(uv, float(layer), ref));
            taps += 1.0;
        }
    return taps > 0.0 ? sum / taps : 1.0;
}
#endif

// Visibility of p from shadow layer `layer`, filtered as pcfRadius and pcfNearest say.
float percentageCloserAt(int layer, vec3 p, vec3 n)
{
    vec4 s = shadowCoordinates(layer, p, n);
    if (s.w == 0.0) return 1.0;
    // A view rendered into the corner [0, scale]^2 of its layer (gl/frame/shadow_maps.h: a spot's or point
    // light's side from its footprint on screen) keeps every tap inside it, pcfRadius + 1 texels from its
    // edges; a whole layer keeps the sampler's clamp at its edges.
    float scale = shadowView(layer).texelWorld.y;
    float margin = scale < 1.0 ? float(pcfRadius + 1) / float(textureSize(shadowMaps, 0).x) : 0.0;
    return percentageCloser(clamp(s.xy, vec2(margin), vec2(scale - margin)), float(layer), s.z);
}

#ifdef RAY_SHADOWS
// Still frames (RAY_SHADOWS, the frame parameter shadow.still=rays): the light's visibility from p by one
// shadow ray through the frame's BVH (common/raycast.glsl), towards the light's position (for an emitting
// mesh this still frame's point on it) or against a directional light's direction. Exact for the point the
// frame samples, with no map's texel and no bias beyond a ray offset of 2e-4 of p's largest coordinate (at
// least 0.2 mm), so that contact shadows converge as the still frames accumulate (issue 59).
float rayVisibility(Light l, vec3 p, vec3 n)
{
    float offset = surfaceRayOffset(p);
    vec3 origin = p + n * offset;
    if (l.type == kLightDirectional) return anyHit(origin, -l.direction, 0.0, 3.0e38) ? 0.0 : 1.0;
    vec3 d = l.position - origin;
    float distance = length(d);
    // Short of the light by as much as the offset: an emitter's point lies on its own triangle.
    float tMax = distance - max(offset, 1e-4 * distance);
    return tMax <= 0.0 || !anyHit(origin, d / distance, 0.0, tMax) ? 1.0 : 0.0;
}
#endif

float shadowVisibility(Light l, vec3 p, vec3 n)
{
    if (l.shadow.x < 0) return 1.0;
#ifdef RAY_SHADOWS
    return rayVisibility(l, p, n);
#endif
    // One call of the filter whatever the light (a SIMD rasteriser such as llvmpipe runs every call site a
    // lane needs: two of them made cornell-spot's direct pass 20% slower).
    int layer = l.shadow.x;
    if (l.shadow.y == 6) {
        layer += cubeFace(p - l.position);
    } else {
#ifdef SHADOW_CASCADES
        // A directional light's cascades (gl/frame/light_views.h), finest first, then its whole-scene view:
        // the first whose map holds p with a filter's margin. Compiled into the still frames' direct pass
        // only (gl/frame/frame.cpp), the frames that render the cascades.
        vec2 margin = vec2(float(pcfRadius + 1)) / vec2(textureSize(shadowMaps, 0).xy);
        for (int k = 1; k < l.shadow.y; ++k, ++layer) {
            vec4 s = shadowCoordinates(layer, p, n);
            if (all(greaterThanEqual(s.xy, margin)) && all(lessThanEqual(s.xy, 1.0 - margin))) break;
        }
#else
        // A spot's one view, or a directional light's view of the whole scene after its cascades.
        layer += l.shadow.y - 1;
#endif
    }
    return percentageCloserAt(layer, p, n);
}

#endif
