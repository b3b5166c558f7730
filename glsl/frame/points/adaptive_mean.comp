#version 450 core
// The key of the display scale of §3.3's L_o (adaptive_select.comp's logAverage): the log-average
// luminance of the frame's light, direct plus L_o, at the first level's samples (Reinhard et al. 2002's
// log-average, robust to a visible emitter), on the GPU in two passes with sums in a fixed order (the same
// key in every run):
// - MEAN_FINAL undefined: one work group per 16 x 16 pixels sums log(kLogDelta + luminance) and the count
//   of its gathered pixels (alpha 1 in the diffuse light image) into one texel of `partials`;
// - MEAN_FINAL: one work group sums every texel of `partials` and writes (sum, count, log-average) to
//   texel 0 (the log-average 0 when nothing was gathered).
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
layout(rgba32f, binding = 3) uniform readonly image2D direct; // the frame's direct light
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
        if (d.a >= 1.0) {
            float l = luminanceOf(px, d.rgb, imageLoad(lightGlossy, px).rgb) + luminance(imageLoad(direct, px).rgb);
            mine = vec2(log(kLogDelta + l), 1.0);
        }
    }
#endif
    vec2 s = groupSum(mine);
    if (t != 0u) return;
#ifdef MEAN_FINAL
    imageStore(partials, ivec2(0), vec4(s, s.y > 0.0 ? exp(s.x / s.y) : 0.0, 0.0));
#else
    imageStore(partials, ivec2(gl_WorkGroupID.xy), vec4(s, 0.0, 0.0));
#endif
}
