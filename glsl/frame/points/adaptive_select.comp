#version 450 core
// "adaptive-select": one level of §3.3's subdivision. First level (spacing 0 in the uniform): every pixel of
// the 4 x 4 grid with geometry is sampled (or of the 1 x 1 grid: every pixel, without adaptive sampling).
// Later levels: a candidate is sampled when the coherence metric over its parents exceeds epsilon, else
// marked for interpolation. L_o is display-scaled as the paper's 8-bit L_o is: radiance here is absolute, so
// it is scaled by adaptive.glsl's kKey over the log-average luminance of the frame's light at the first
// level's samples and clamped at 1.
#include "common/bindings.glsl"
#include "frame/points/adaptive.glsl"
#include "frame/points/bindings.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(r8ui, binding = 0) uniform uimage2D pixelState;
layout(rgba32f, binding = 1) uniform readonly image2D lightDiffuse;
layout(rgba32f, binding = 2) uniform readonly image2D lightGlossy;
// The list's length, counted up here, then its targets (frame/points/bindings.glsl, SSBO_GATHER_TARGETS).
layout(std430, binding = SSBO_GATHER_TARGETS) buffer GatherTargets { uint gatherCount; uint gatherPad; uvec2 gatherTargets[]; };
uniform int firstGrid;   // > 0: the first level, every pixel of this grid
uniform float epsilon;
uniform float lambda;
uniform float logAverage; // the log-average luminance of the frame's light at the first level's samples

float outgoingLuminance(ivec2 px)
{
    return luminanceOf(px, imageLoad(lightDiffuse, px).rgb, imageLoad(lightGlossy, px).rgb);
}

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, viewSize))) return;
    bool take = false;
    if (firstGrid > 0) {
        if (!onGrid(px, firstGrid)) return;
        if (!hasGeometry(px)) {
            imageStore(pixelState, px, uvec4(kNoGeometry));
            return;
        }
        take = true;
    } else {
        int halfSpacing = spacing / 2;
        if (!onGrid(px, halfSpacing) || onGrid(px, spacing)) return;
        if (!hasGeometry(px)) {
            imageStore(pixelState, px, uvec4(kNoGeometry));
            return;
        }
        ivec2 lo, hi;
        parentBox(px, spacing, lo, hi);
        ivec2 parents[4] = ivec2[4](lo, ivec2(hi.x, lo.y), ivec2(lo.x, hi.y), hi);
        GSurface own = gbufferSurface(px);
        vec3 pc = own.position, nc = own.normal;
        float radianceScale = logAverage > 0.0 ? kKey / logAverage : 0.0;
        float geometric = 0.0, l[4];
        for (int i = 0; i < 4; ++i) {
            if (!hasGeometry(parents[i])) {
                geometric = 1e30; // a parent off the surface: an edge
                l[i] = 0.0;
                continue;
            }
            geometric = max(geometric, geometricTerm(parents[i], pc, nc));
            l[i] = min(outgoingLuminance(parents[i]) * radianceScale, 1.0);
        }
        float radiance = 0.0;
        for (int j = 0; j < 4; ++j)
            for (int k = j + 1; k < 4; ++k) radiance += abs(l[j] - l[k]);
        take = geometric + lambda * radiance > epsilon;
        if (!take) imageStore(pixelState, px, uvec4(kInterpolated));
    }
    if (take) {
        imageStore(pixelState, px, uvec4(kSampled));
        uint k = atomicAdd(gatherCount, 1u);
        gatherTargets[k] = uvec2(uint(px.x) | (uint(px.y) << 16), 0u); // level 0, no neighbour mask
    }
}
