#version 450 core
// "compose": indirect light = the pixel's own diffuse colour x the diffuse part + the glossy part; in
// progressive mode the running mean over the frames since the last restart (weight 1 / frames).
#include "common/bindings.glsl"
#include "frame/points/adaptive.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform readonly image2D lightDiffuse;
layout(rgba32f, binding = 1) uniform readonly image2D lightGlossy;
layout(rgba32f, binding = 2) uniform image2D accumulated;
layout(rgba32f, binding = 3) uniform writeonly image2D indirectOut;
uniform float newWeight; // 1 / frames accumulated, this one included

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, viewSize))) return;
    vec3 l = vec3(0.0);
    if (hasGeometry(px))
        l = gbufferDiffuse(px).rgb * imageLoad(lightDiffuse, px).rgb + imageLoad(lightGlossy, px).rgb;
    // The first frame of a run replaces what the image holds without reading it: new storage is undefined
    // (NaN on some drivers, and NaN x 0 is NaN).
    vec3 mean = newWeight >= 1.0 ? l : mix(imageLoad(accumulated, px).rgb, l, newWeight);
    imageStore(accumulated, px, vec4(mean, 1.0));
    imageStore(indirectOut, px, vec4(mean, 1.0));
}
