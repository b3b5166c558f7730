#version 450 core
// One level of the eye-space min-max pyramid of §3.2 (Fig. 2b-c; common/multires.glsl): level
// `level` >= 1 from its four children at level - 1 (the G-buffer for level 1). Children beyond the
// previous level's size are absent (odd sizes), pixels without geometry take no part. Besides the depth
// and normal ranges that detect discontinuities, each patch keeps the means of its pixels with geometry
// (position, normal, diffuse colour): the representative the gather shades (§3.2.2). The patch is
// classified here once (empty, continuous, discontinuity) for the stencil pass.
// FROM_GBUFFER: the program for level 1, whose children are pixels; without it, levels 2 and up. Two
// programs, and the four children unrolled: on a SIMD rasteriser (llvmpipe) one program for both ran
// loadPatch's G-buffer path and its pyramid path for every child (the two take 0.6 of its time there).
// A compute pass, not the paper's render-to-texture: as fast on llvmpipe as a fragment pass into the six
// targets (measured, within the machine's noise), and 4.5 times faster on an H200, whose graphics units
// are few (0.027 against 0.122 ms).
#include "common/multires.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform writeonly image2D outPosition;
layout(rgba16f, binding = 1) uniform writeonly image2D outNormal;
layout(rgba16f, binding = 2) uniform writeonly image2D outDiffuse;
layout(rg32f, binding = 3) uniform writeonly image2D outDepthRange;
layout(rgba16f, binding = 4) uniform writeonly image2D outNormalMin;
layout(rgba16f, binding = 5) uniform writeonly image2D outNormalMax;

uniform int level;

void addChild(inout MultiresPatch r, inout vec3 positionSum, inout vec3 normalSum, inout vec3 diffuseSum, ivec2 c)
{
#ifdef FROM_GBUFFER
    MultiresPatch p = loadPixel(c);
#else
    MultiresPatch p = loadPyramidPatch(level - 1, c);
#endif
    if (p.count == 0.0) return;
    r.count += p.count;
    positionSum += p.count * p.position;
    normalSum += p.count * p.normal;
    diffuseSum += p.count * p.diffuse;
    r.depthRange = vec2(min(r.depthRange.x, p.depthRange.x), max(r.depthRange.y, p.depthRange.y));
    r.normalMin = min(r.normalMin, p.normalMin);
    r.normalMax = max(r.normalMax, p.normalMax);
}

void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (!levelContains(level, t)) return;
    MultiresPatch r = emptyPatch();
    vec3 positionSum = vec3(0.0), normalSum = vec3(0.0), diffuseSum = vec3(0.0);
    addChild(r, positionSum, normalSum, diffuseSum, 2 * t);
    addChild(r, positionSum, normalSum, diffuseSum, 2 * t + ivec2(1, 0));
    addChild(r, positionSum, normalSum, diffuseSum, 2 * t + ivec2(0, 1));
    addChild(r, positionSum, normalSum, diffuseSum, 2 * t + ivec2(1, 1));
    float inv = r.count > 0.0 ? 1.0 / r.count : 0.0;
    ivec2 a = pyramidTexel(level, t);
    imageStore(outPosition, a, vec4(positionSum * inv, r.count));
    float state = r.count == 0.0 ? kPatchEmpty
                : rangesDiscontinuous(r.depthRange, r.normalMin, r.normalMax) ? kPatchDiscontinuous : kPatchContinuous;
    imageStore(outNormal, a, vec4(normalSum * inv, state));
    imageStore(outDiffuse, a, vec4(diffuseSum * inv, 0.0));
    imageStore(outDepthRange, a, vec4(r.depthRange, 0.0, 0.0));
    imageStore(outNormalMin, a, vec4(r.normalMin, 0.0));
    imageStore(outNormalMax, a, vec4(r.normalMax, 0.0));
}
