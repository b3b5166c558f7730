#version 450 core
// "compose": indirect light = the pixel's own diffuse colour x the diffuse part + the glossy part; in
// progressive mode the running mean over the frames since the last restart (weight 1 / frames).
//
// With postFilter = r > 0, both parts are first taken through the paper's post-process filter (Maletz,
// Wang & Bowers 2011, §4: "a 7 x 7 joint bilateral filter on the computed indirect lighting buffer",
// reduced to 3 x 3 for scenes with glossy objects): a (2r + 1)^2 window weighed by a Gaussian of the pixel
// offset (sigma = (r + 1) / 2) times exp(-4 g^2), g the coherence metric's geometric term between the
// neighbour and the pixel, as the interpolation weighs parents (adaptive_interpolate.comp). The paper names
// the filter, not its weights: these are the ones the rest of §3.3 uses. Pixels without geometry give no
// light. r is a uniform: every lane runs the same window.
#include "common/bindings.glsl"
#include "frame/points/adaptive.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform readonly image2D lightDiffuse;
layout(rgba32f, binding = 1) uniform readonly image2D lightGlossy;
layout(rgba32f, binding = 2) uniform image2D accumulated;
layout(rgba32f, binding = 3) uniform writeonly image2D indirectOut;
uniform float newWeight; // 1 / frames accumulated, this one included
uniform int postFilter;  // the window's half-width r; 0: no filter

// The pixel's two light parts, through the post-filter where there is one.
void lightAt(ivec2 px, out vec3 diffuse, out vec3 glossy)
{
    if (postFilter == 0) {
        diffuse = imageLoad(lightDiffuse, px).rgb;
        glossy = imageLoad(lightGlossy, px).rgb;
        return;
    }
    float sigma = 0.5 * float(postFilter + 1);
    GSurface own = gbufferSurface(px);
    diffuse = vec3(0.0);
    glossy = vec3(0.0);
    float wsum = 0.0;
    for (int dy = -postFilter; dy <= postFilter; ++dy)
        for (int dx = -postFilter; dx <= postFilter; ++dx) {
            ivec2 q = px + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, viewSize)) || !hasGeometry(q)) continue;
            float geo = geometricTerm(q, own.position, own.normal);
            float w = exp(-float(dx * dx + dy * dy) / (2.0 * sigma * sigma) - 4.0 * geo * geo);
            diffuse += w * imageLoad(lightDiffuse, q).rgb;
            glossy += w * imageLoad(lightGlossy, q).rgb;
            wsum += w;
        }
    // The pixel itself weighs 1 (g = 0), so wsum >= 1.
    diffuse /= wsum;
    glossy /= wsum;
}

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, viewSize))) return;
    vec3 l = vec3(0.0);
    if (hasGeometry(px)) {
        vec3 diffuse, glossy;
        lightAt(px, diffuse, glossy);
        l = gbufferDiffuse(px).rgb * diffuse + glossy;
    }
    // The first frame of a run replaces what the image holds without reading it: new storage is undefined
    // (NaN on some drivers, and NaN x 0 is NaN).
    vec3 mean = newWeight >= 1.0 ? l : mix(imageLoad(accumulated, px).rgb, l, newWeight);
    imageStore(accumulated, px, vec4(mean, 1.0));
    imageStore(indirectOut, px, vec4(mean, 1.0));
}
