#version 450 core
// One level of the eye-space min-max pyramid of §3.2 (Fig. 2b-c; common/multires.glsl): level
// `level` >= 1 from its four children at level - 1 (the G-buffer for level 1). Children beyond the
// previous level's size are absent (odd sizes), pixels without geometry take no part. Besides the depth
// and normal ranges that detect discontinuities, each patch keeps the means of its pixels with geometry
// (position, normal, diffuse colour): the representative the gather shades (§3.2.2). The patch is
// classified here once (empty, continuous, discontinuity) for the stencil pass.
#include "common/multires.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform writeonly image2D outPosition;
layout(rgba16f, binding = 1) uniform writeonly image2D outNormal;
layout(rgba16f, binding = 2) uniform writeonly image2D outDiffuse;
layout(rg32f, binding = 3) uniform writeonly image2D outDepthRange;
layout(rgba16f, binding = 4) uniform writeonly image2D outNormalMin;
layout(rgba16f, binding = 5) uniform writeonly image2D outNormalMax;

uniform int level;

void main()
{
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (!levelContains(level, t)) return;
    MultiresPatch r = emptyPatch();
    vec3 positionSum = vec3(0.0), normalSum = vec3(0.0), diffuseSum = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        MultiresPatch c = loadPatch(level - 1, 2 * t + ivec2(i & 1, i >> 1));
        if (c.count == 0.0) continue;
        r.count += c.count;
        positionSum += c.count * c.position;
        normalSum += c.count * c.normal;
        diffuseSum += c.count * c.diffuse;
        r.depthRange = vec2(min(r.depthRange.x, c.depthRange.x), max(r.depthRange.y, c.depthRange.y));
        r.normalMin = min(r.normalMin, c.normalMin);
        r.normalMax = max(r.normalMax, c.normalMax);
    }
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
