#version 450 core
// Still frames (gl/frame/frame.h, Frame::accumulate): the running mean of the frames rendered since the
// view last changed, each with its samples at another point inside the pixel.
//   default               accumulated = mean of `current` (the frame's result: direct, or direct + indirect)
//   ADD_INDIRECT          accumulated = mean of `current` (the direct light); result = it + the mean of
//                         `indirect` over the still frames with frame n weighing n^3. A progressive
//                         technique's indirect light is already its own running mean, but each frame shows
//                         it at that frame's sample position in the pixel (grb's bilinear atlas lookup at a
//                         silhouette or beside a bright texel changed a pixel from 8.3 to 3.6 between two
//                         frames): the pixel needs its mean over the positions too. Weights growing as n^3
//                         let the early, less converged frames fade (the first half of the frames holds
//                         1/16 of the weight); weights n kept enough of them to make cornell-area's error
//                         at 256x256 after 300 frames 5.2% where the latest frame alone gave 4.0% (n^3:
//                         4.4%, and the pixels box-filtered).
#include "common/bindings.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = UNIT_COMPOSITE_DIRECT) uniform sampler2D current;
layout(rgba32f, binding = 0) uniform image2D accumulated;
#ifdef ADD_INDIRECT
layout(binding = UNIT_COMPOSITE_INDIRECT) uniform sampler2D indirect;
layout(rgba32f, binding = 1) writeonly uniform image2D result;
layout(rgba32f, binding = 2) uniform image2D accumulatedIndirect;
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
    // The weighted mean's increment: sum_t t^3 x_t / sum_t t^3, old + (new - old) 4 n / (n + 1)^2.
    vec3 ind = texelFetch(indirect, px, 0).rgb;
    vec3 im = stillFrame <= 1 ? ind : imageLoad(accumulatedIndirect, px).rgb;
    float n = float(stillFrame);
    if (stillFrame > 1) im += (ind - im) * (4.0 * n / ((n + 1.0) * (n + 1.0)));
    imageStore(accumulatedIndirect, px, vec4(im, 1.0));
    imageStore(result, px, vec4(mean + im, 1.0));
#endif
}
