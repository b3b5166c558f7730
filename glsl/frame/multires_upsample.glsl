// Upsample and combine (§3.2.2, after [NW09]): full-resolution indirect light from the flattened
// multiresolution illumination buffer (gl/frame/multires.cpp runs it as a fragment pass into the frame's
// indirect texture on a software rasteriser, as a compute pass elsewhere: frame/multires_upsample.frag,
// .comp). For each pixel with geometry:
//  1. its level k: the one level whose patch p >> k covering it is a valid fragment (alpha >= 1; exactly
//     one exists, common/multires.glsl);
//  2. k = 0: that pixel's own value. k >= 1: bilinear interpolation at the pixel centre among the four
//     nearest level-k patch centres, keeping only neighbours that are themselves valid at level k and
//     that lie on the same smooth surface as the pixel's own patch (multires.glsl: sameSurface; the
//     stencil pass stored which of its 8 neighbours qualify as a mask in the alpha channel). The
//     pixel's own patch always counts (its bilinear weight is at least 1/4); the kept weights are
//     renormalised. So light is blended across patch borders on smooth surfaces, never across edges,
//     and never with fragments of other levels;
//  3. times the pixel's own diffuse colour rho_i (the gather left it out): Eq. 5's rho_i at full resolution.
// UNMODULATED: a second buffer (rgb, the flattened layout) is interpolated with the same weights and
// added as it is, not times rho_i: glossy reflected radiance (point-based final gathering, gl/frame/points/).
#ifndef BOUNCE_MULTIRES_UPSAMPLE_GLSL
#define BOUNCE_MULTIRES_UPSAMPLE_GLSL

#include "common/multires.glsl"

layout(binding = UNIT_MULTIRES_ILLUMINATION) uniform sampler2D mrIllumination;
#ifdef UNMODULATED
layout(binding = UNIT_MULTIRES_UNMODULATED) uniform sampler2D mrUnmodulated;
vec3 unmodulatedAt(int level, ivec2 t) { return texelFetch(mrUnmodulated, levelOrigin[level] + t, 0).rgb; }
#else
vec3 unmodulatedAt(int level, ivec2 t) { return vec3(0.0); }
#endif

vec4 illuminationAt(int level, ivec2 t) { return texelFetch(mrIllumination, levelOrigin[level] + t, 0); }

// The indirect light of pixel px.
vec3 upsampled(ivec2 px)
{
    vec3 result = vec3(0.0);
    if (gbufferHasGeometry(px)) {
        int k = -1;
        for (int l = 0; l <= coarsestLevel && k < 0; ++l)
            if (illuminationAt(l, px >> l).a >= 1.0) k = l;
        vec3 e = vec3(0.0), g = vec3(0.0);
        if (k == 0) {
            e = illuminationAt(0, px).rgb;
            g = unmodulatedAt(0, px);
        } else if (k > 0) {
            ivec2 own = px >> k;
            vec4 ownValue = illuminationAt(k, own);
            uint neighbours = uint(ownValue.a) - 1u; // the stencil pass's mask of same-surface neighbours
            vec2 u = (vec2(px) + 0.5) / float(1 << k) - 0.5;
            ivec2 base = ivec2(floor(u));
            vec2 f = u - vec2(base);
            float wsum = 0.0;
            for (int i = 0; i < 4; ++i) {
                ivec2 o2 = ivec2(i & 1, i >> 1);
                ivec2 c = base + o2;
                float w = (o2.x == 1 ? f.x : 1.0 - f.x) * (o2.y == 1 ? f.y : 1.0 - f.y);
                if (w <= 0.0) continue;
                if (c != own) {
                    if ((neighbours & neighbourBit(c - own)) == 0u) continue;
                    e += w * illuminationAt(k, c).rgb;
                    g += w * unmodulatedAt(k, c);
                } else {
                    e += w * ownValue.rgb;
                    g += w * unmodulatedAt(k, own);
                }
                wsum += w;
            }
            e /= wsum; // the own patch's weight is at least 1/4
            g /= wsum;
        }
        result = gbufferDiffuse(px).rgb * e + g;
    }
    return result;
}

#endif
