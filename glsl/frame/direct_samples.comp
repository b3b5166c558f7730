#version 450 core
// "direct.samples" (gl/frame/frame.h, renderDirectSubsamples): a still frame's direct light at its further
// points in the pixel summed (sum = direct at the first, sum + direct after), then, with RESOLVE, the frame's
// own direct light replaced by the mean of all its points: (sum + direct) / still.directSamples.
layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform image2D direct;
layout(rgba32f, binding = 1) uniform image2D sum;

uniform int first;   // the first further point: the sum starts (its texels hold an earlier frame's, or nothing)
uniform float scale; // RESOLVE: 1 / still.directSamples

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(direct)))) return;
    vec4 d = imageLoad(direct, p);
#ifdef RESOLVE
    imageStore(direct, p, (imageLoad(sum, p) + d) * scale);
#else
    // A select, not a product with 0: an unwritten texel may hold anything, NaN included.
    imageStore(sum, p, first != 0 ? d : imageLoad(sum, p) + d);
#endif
}
