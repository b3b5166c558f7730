#version 450 core
// Joint bilateral upsampling of indirect light from a coarser frame (gl/frame/joint_upsample.h): the
// four nearest coarse pixels, bilinear weights, kept only on this pixel's surface (eye depth and normal
// from both G-buffers); none kept: the coarse pixel of nearest depth.
#include "common/bindings.glsl"
#include "common/packing.glsl"
layout(binding = UNIT_UPSAMPLE_COARSE_INDIRECT) uniform sampler2D coarseIndirect;
// The two frames' gGeometry (common/gbuffer.glsl): eye depth bits (0: none) and the octahedral normal.
layout(binding = UNIT_UPSAMPLE_COARSE_GEOMETRY) uniform usampler2D coarseGeometry;
layout(binding = UNIT_UPSAMPLE_FULL_GEOMETRY) uniform usampler2D fullGeometry;

// xyz normal, w eye depth (0: no geometry).
vec4 normalDepth(uvec2 g) { return g.x == 0u ? vec4(0.0) : vec4(unpackUnitVector(g.y), uintBitsToFloat(g.x)); }

uniform ivec2 coarseSize;
uniform vec2 scale; // coarse pixels per full pixel
uniform float depthTolerance;
uniform float normalTolerance;

layout(location = 0) out vec4 outIndirect;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 own = normalDepth(texelFetch(fullGeometry, px, 0).xy);
    if (own.w <= 0.0) { outIndirect = vec4(0.0, 0.0, 0.0, 1.0); return; } // background
    vec2 u = (vec2(px) + 0.5) * scale - 0.5;
    ivec2 base = ivec2(floor(u));
    vec2 f = u - vec2(base);
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    vec3 nearest = vec3(0.0);
    float nearestGap = 1e30;
    for (int i = 0; i < 4; ++i) {
        ivec2 o = ivec2(i & 1, i >> 1);
        ivec2 c = clamp(base + o, ivec2(0), coarseSize - 1);
        vec4 nd = normalDepth(texelFetch(coarseGeometry, c, 0).xy);
        if (nd.w <= 0.0) continue;
        vec3 value = texelFetch(coarseIndirect, c, 0).rgb;
        float gap = abs(nd.w - own.w);
        if (gap < nearestGap) { nearestGap = gap; nearest = value; }
        bool sameSurface = gap <= depthTolerance * own.w && dot(nd.xyz, own.xyz) >= 1.0 - normalTolerance;
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        if (sameSurface && w > 0.0) {
            sum += w * value;
            wsum += w;
        }
    }
    outIndirect = vec4(wsum > 0.0 ? sum / wsum : nearest, 1.0);
}
