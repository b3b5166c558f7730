#version 450 core
// One level of the eye-space min-max pyramid of §3.2 (Fig. 2b-c; common/multires.glsl), as the paper
// builds it: a fragment pass per level into the pyramid's six targets (gl/frame/multires.cpp), level
// `level` >= 1 from its four children at level - 1 (the G-buffer for level 1), read from the same
// textures the pass renders into: the regions of two levels are disjoint and a texture barrier separates
// the levels' draws (GL 4.5, 9.3.1). Children beyond the previous level's size are absent (odd sizes),
// pixels without geometry take no part. Besides the depth and normal ranges that detect discontinuities,
// each patch keeps the means of its pixels with geometry (position, normal, diffuse colour): the
// representative the gather shades (§3.2.2). The patch is classified here once (empty, continuous,
// discontinuity) for the stencil pass.
// FROM_GBUFFER: the program for level 1, whose children are pixels; without it, levels 2 and up. Two
// programs, and the four children unrolled: on a SIMD rasteriser (llvmpipe) one program for both would run
// loadPatch's G-buffer path and its pyramid path for every child, and a loop keeps the running patch in
// memory (together five times this pass's time, measured).
#include "common/multires.glsl"

uniform int level;

layout(location = 0) out vec4 outPosition;   // mrPosition
layout(location = 1) out vec4 outNormal;     // mrNormal
layout(location = 2) out vec4 outDiffuse;    // mrDiffuse
layout(location = 3) out vec4 outDepthRange; // mrDepthRange
layout(location = 4) out vec4 outNormalMin;  // mrNormalMin
layout(location = 5) out vec4 outNormalMax;  // mrNormalMax

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
    ivec2 t = ivec2(gl_FragCoord.xy) - pyramidTexel(level, ivec2(0));
    MultiresPatch r = emptyPatch();
    vec3 positionSum = vec3(0.0), normalSum = vec3(0.0), diffuseSum = vec3(0.0);
    addChild(r, positionSum, normalSum, diffuseSum, 2 * t);
    addChild(r, positionSum, normalSum, diffuseSum, 2 * t + ivec2(1, 0));
    addChild(r, positionSum, normalSum, diffuseSum, 2 * t + ivec2(0, 1));
    addChild(r, positionSum, normalSum, diffuseSum, 2 * t + ivec2(1, 1));
    float inv = r.count > 0.0 ? 1.0 / r.count : 0.0;
    float state = r.count == 0.0 ? kPatchEmpty
                : rangesDiscontinuous(r.depthRange, r.normalMin, r.normalMax) ? kPatchDiscontinuous : kPatchContinuous;
    outPosition = vec4(positionSum * inv, r.count);
    outNormal = vec4(normalSum * inv, state);
    outDiffuse = vec4(diffuseSum * inv, 0.0);
    outDepthRange = vec4(r.depthRange, 0.0, 0.0);
    outNormalMin = vec4(r.normalMin, 0.0);
    outNormalMax = vec4(r.normalMax, 0.0);
}
