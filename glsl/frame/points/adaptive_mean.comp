#version 450 core
// The mean outgoing luminance of the first level's samples (adaptive_select.comp's radianceScale), on the
// GPU in two passes with sums in a fixed order (the same mean in every run):
// - MEAN_FINAL undefined: one work group per 16 x 16 pixels sums the luminance and the count of its
//   gathered pixels (alpha 1 in the diffuse light image) into one texel of `partials`;
// - MEAN_FINAL: one work group sums every texel of `partials` and writes (sum, count, mean) to texel 0.
// It replaced reading three full-size images back to the CPU every frame (an NVIDIA H200's
// "adaptive-select" took 16-31 ms at 1024x768).
#include "frame/points/adaptive.glsl"

layout(local_size_x = 16, local_size_y = 16) in;
#define GROUP_SUM_TYPE vec2
#define GROUP_SUM_SIZE 256
#include "common/group_sum.glsl"

#ifdef MEAN_FINAL
layout(rgba32f, binding = 0) uniform image2D partials;
#else
layout(rgba32f, binding = 0) uniform readonly image2D lightDiffuse;
layout(rgba32f, binding = 1) uniform readonly image2D lightGlossy;
layout(rgba32f, binding = 2) uniform writeonly image2D partials;
#endif

void main()
{
    uint t = gl_LocalInvocationIndex;
    vec2 mine = vec2(0.0);
#ifdef MEAN_FINAL
    ivec2 size = imageSize(partials);
    for (int i = int(t); i < size.x * size.y; i += 256) mine += imageLoad(partials, ivec2(i % size.x, i / size.x)).xy;
#else
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(px, viewSize))) {
        vec4 d = imageLoad(lightDiffuse, px);
        if (d.a >= 1.0) mine = vec2(luminanceOf(px, d.rgb, imageLoad(lightGlossy, px).rgb), 1.0);
    }
#endif
    vec2 s = groupSum(mine);
    if (t != 0u) return;
#ifdef MEAN_FINAL
    imageStore(partials, ivec2(0), vec4(s, s.y > 0.0 ? s.x / s.y : 0.0, 0.0));
#else
    imageStore(partials, ivec2(gl_WorkGroupID.xy), vec4(s, 0.0, 0.0));
#endif
}
