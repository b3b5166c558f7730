// Shadow-map visibility for every light type: all shadow views live in one depth array (a spot uses one
// perspective layer, a point light or an area light six cube-face layers, a directional light one
// orthographic layer). Hardware depth comparison; PCF over a (2r+1)^2 kernel, r = pcfRadius.
#ifndef BOUNCE_SHADOW_GLSL
#define BOUNCE_SHADOW_GLSL

#include "common/scene.glsl"

layout(binding = UNIT_SHADOW_MAPS) uniform sampler2DArrayShadow shadowMaps;
uniform int pcfRadius;

float shadowVisibility(Light l, vec3 p, vec3 n)
{
    if (l.shadow.x < 0) return 1.0;
    int layer = l.shadow.x;
    if (l.shadow.y == 6) layer += cubeFace(p - l.positionType.xyz);
    ShadowView v = shadowViews[layer];
    // Normal offset by about one and a half texels at the receiver's distance, so that lit surfaces
    // do not shadow themselves at grazing angles; the constant bias below covers the rest.
    float dist = v.originFar.w > 0.0 ? length(p - v.originFar.xyz) : 1.0;
    vec3 q = p + n * (1.5 * v.texelWorld.x * dist);
    vec4 c = v.viewProj * vec4(q, 1.0);
    vec3 s = c.xyz / c.w * 0.5 + 0.5;
    if (c.w <= 0.0 || s.z > 1.0) return 1.0;
    s.xy = clamp(s.xy, vec2(0.0), vec2(1.0));
    vec2 texel = 1.0 / vec2(textureSize(shadowMaps, 0).xy);
    float ref = s.z - 2e-5;
    float sum = 0.0;
    for (int y = -pcfRadius; y <= pcfRadius; ++y)
        for (int x = -pcfRadius; x <= pcfRadius; ++x)
            sum += texture(shadowMaps, vec4(s.xy + vec2(x, y) * texel, float(layer), ref));
    float taps = float((2 * pcfRadius + 1) * (2 * pcfRadius + 1));
    return sum / taps;
}

#endif
