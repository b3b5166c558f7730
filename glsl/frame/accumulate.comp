#version 450 core
// Still frames (gl/frame/frame.h, Frame::accumulate): the running mean of the frames rendered since the
// view last changed, each with its samples at another point inside the pixel.
//   default               accumulated = mean of `current` (the frame's result: direct, or direct + indirect)
//   ADD_INDIRECT          accumulated = mean of `current` (the direct light); result = it + `indirect`
//                         (a progressive technique's indirect light, already its own running mean)
#include "common/bindings.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = UNIT_COMPOSITE_DIRECT) uniform sampler2D current;
layout(rgba32f, binding = 0) uniform image2D accumulated;
#ifdef ADD_INDIRECT
layout(binding = UNIT_COMPOSITE_INDIRECT) uniform sampler2D indirect;
layout(rgba32f, binding = 1) writeonly uniform image2D result;
#endif

uniform int stillFrame; // 1 for the first still frame (the mean restarts), then 2, 3, ...

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, imageSize(accumulated)))) return;
    vec3 c = texelFetch(current, px, 0).rgb;
    // The incremental mean: exact for the first frame (weight 1), then old + (new - old) / n.
    vec3 mean = stillFrame <= 1 ? c : imageLoad(accumulated, px).rgb;
    if (stillFrame > 1) mean += (c - mean) / float(stillFrame);
    imageStore(accumulated, px, vec4(mean, 1.0));
#ifdef ADD_INDIRECT
    imageStore(result, px, vec4(mean + texelFetch(indirect, px, 0).rgb, 1.0));
#endif
}
