// Shadow-map visibility for every light type: all shadow views live in one depth array (a spot uses one
// perspective layer, a point light or an area light six cube-face layers, a directional light one
// orthographic layer). Hardware depth comparison; PCF over a (2r+1)^2 kernel, r = pcfRadius (pcfNearest: the
// taps unfiltered), set on every program that includes this file (ShadowMaps::setPcfUniforms).
#ifndef BOUNCE_SHADOW_GLSL
#define BOUNCE_SHADOW_GLSL

#include "common/scene.glsl"

layout(binding = UNIT_SHADOW_MAPS) uniform sampler2DArrayShadow shadowMaps;
uniform int pcfRadius;
uniform int pcfNearest; // 1: nearest taps (shadow.linear off); 0, the default: 2x2 bilinear comparisons
// The receiver's offset along its normal, in texels at its distance (ShadowMaps::setPcfUniforms): 1.5 for
// filtered taps, less in still frames, whose jittered nearest taps need no margin for a filter's footprint
// and whose mean would keep the offset's shift of every contact shadow.
uniform float shadowNormalOffset = 1.5;
// 0: a directional light's cascades are not rendered this frame (moving), only its whole-scene view is read.
uniform int shadowCascades = 1;

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
    ShadowView v = shadowViews[layer];
    // Normal offset by shadowNormalOffset texels at the receiver's distance, so that lit surfaces do not
    // shadow themselves at grazing angles; the constant bias below covers the rest.
    float dist = v.originFar.w > 0.0 ? length(p - v.originFar.xyz) : 1.0;
    vec3 q = p + n * (shadowNormalOffset * v.texelWorld.x * dist);
    vec4 c = v.viewProj * vec4(q, 1.0);
    vec3 s = c.xyz / c.w * 0.5 + 0.5;
    return vec4(s.xy, s.z - 2e-5, c.w <= 0.0 || s.z > 1.0 ? 0.0 : 1.0);
}

float shadowVisibility(Light l, vec3 p, vec3 n)
{
    if (l.shadow.x < 0) return 1.0;
    int layer = l.shadow.x;
    if (l.shadow.y == 6) layer += cubeFace(p - l.positionType.xyz);
    bool cascades = l.shadow.y > 1 && l.shadow.y != 6;
    if (cascades && shadowCascades == 0) layer += l.shadow.y - 1;
    vec4 s = shadowCoordinates(layer, p, n);
    // A directional light's cascades (gl/frame/light_views.h), finest first, then its whole-scene view:
    // the first whose map holds p with a filter's margin.
    for (int k = 1; k < l.shadow.y && cascades && shadowCascades != 0; ++k) {
        vec2 margin = vec2(float(pcfRadius + 1)) / vec2(textureSize(shadowMaps, 0).xy);
        if (all(greaterThanEqual(s.xy, margin)) && all(lessThanEqual(s.xy, 1.0 - margin))) break;
        s = shadowCoordinates(++layer, p, n);
    }
    if (s.w == 0.0) return 1.0;
    return percentageCloser(clamp(s.xy, vec2(0.0), vec2(1.0)), float(layer), s.z);
}

#endif
