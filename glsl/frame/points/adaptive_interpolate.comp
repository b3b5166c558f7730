#version 450 core
// "interpolate": the candidates of this level that were not sampled take their parents' light by joint
// bilateral weights (Sloan et al. 2007, §3.3): bilinear weights times exp(-4 g^2), g the geometric term of
// the coherence metric between parent and pixel (0 on one smooth surface).
#include "common/bindings.glsl"
#include "frame/points/adaptive.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(r8ui, binding = 0) uniform readonly uimage2D pixelState;
layout(rgba32f, binding = 1) uniform image2D lightDiffuse;
layout(rgba32f, binding = 2) uniform image2D lightGlossy;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, viewSize))) return;
    int halfSpacing = spacing / 2;
    if (!onGrid(px, halfSpacing) || onGrid(px, spacing) || imageLoad(pixelState, px).r != kInterpolated) return;
    ivec2 lo, hi;
    parentBox(px, spacing, lo, hi);
    vec2 f = vec2(hi.x > lo.x ? float(px.x - lo.x) / float(hi.x - lo.x) : 0.0,
                  hi.y > lo.y ? float(px.y - lo.y) / float(hi.y - lo.y) : 0.0);
    ivec2 parents[4] = ivec2[4](lo, ivec2(hi.x, lo.y), ivec2(lo.x, hi.y), hi);
    float bilinear[4] = float[4]((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    GSurface own = gbufferSurface(px);
    vec3 pc = own.position, nc = own.normal;
    vec3 d = vec3(0.0), g = vec3(0.0);
    float wsum = 0.0;
    for (int i = 0; i < 4; ++i) {
        if (bilinear[i] <= 0.0 || !hasGeometry(parents[i])) continue;
        float geo = geometricTerm(parents[i], pc, nc);
        float w = bilinear[i] * exp(-4.0 * geo * geo);
        d += w * imageLoad(lightDiffuse, parents[i]).rgb;
        g += w * imageLoad(lightGlossy, parents[i]).rgb;
        wsum += w;
    }
    if (wsum > 0.0) {
        d /= wsum;
        g /= wsum;
    }
    imageStore(lightDiffuse, px, vec4(d, 0.0));
    imageStore(lightGlossy, px, vec4(g, 0.0));
}
