#version 450 core
// The indirect light at each pixel: the reflected part of the atlas (radiance.glsl: the indirect sums
// over their counts, bilinearly among the texels that took samples) times the pixel's own diffuse colour
// and Fresnel transmission towards the eye, from the G-buffer (sharp textures, back faces black);
// FINAL_GLOSSY: plus the final glossy bounce gathered at the pixel (Sec. 5.3). SHOW_EMITTED (emitters=bundles,
// Sec. 5.1): the light the bundles carried from emitting surfaces (the direct atlas, whose counts are the
// indirect atlas's) is shown too, and the frame leaves it out of its direct light. Without it the frame's
// direct light holds it. The seed (punctual lights) is never shown: the frame computes it.
#include "common/brdf.glsl"
#include "common/gbuffer.glsl"
#include "technique/grb/bindings.glsl"

layout(binding = UNIT_GRB_SENDER_INDIRECT) uniform sampler2D atlasIndirect;
#ifdef SHOW_EMITTED
layout(binding = UNIT_GRB_SENDER_DIRECT) uniform sampler2D atlasDirect;
#endif
#ifdef FINAL_GLOSSY
layout(binding = UNIT_GRB_FINAL_GLOSSY) uniform sampler2D finalGlossy;
#endif
uniform vec3 cameraPosition;

in vec2 vAtlas;
layout(location = 0) out vec4 outIndirect;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    GSurface surface = gbufferSurface(px);
    if (!surface.geometry) {
        outIndirect = vec4(0.0);
        return;
    }
    vec3 n = surface.normal;
    BrdfParams b = gbufferBrdf(px);
    vec3 wo = normalize(cameraPosition - surface.position);

    // Bilinear among the four nearest texels, each its sum over its own count; texels without a sample
    // (empty, or never found in a k-buffer) take no part.
    vec2 q = vAtlas - 0.5;
    ivec2 base = ivec2(floor(q));
    vec2 f = q - vec2(base);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            vec4 v = texelFetch(atlasIndirect, base + ivec2(i, j), 0);
#ifdef SHOW_EMITTED
            v.rgb += texelFetch(atlasDirect, base + ivec2(i, j), 0).rgb;
#endif
            float w = (i == 1 ? f.x : 1.0 - f.x) * (j == 1 ? f.y : 1.0 - f.y);
            if (v.a > 0.0 && w > 0.0) {
                sum += w * v.rgb / v.a;
                weights += w;
            }
        }
    vec3 radiance = weights > 0.0 ? b.diffuse * brdfTransmission(b, max(dot(n, wo), 0.0)) * sum / weights : vec3(0.0);
#ifdef FINAL_GLOSSY
    vec4 g = texelFetch(finalGlossy, px, 0);
    radiance += g.rgb / max(g.a, 1.0);
#endif
    outIndirect = vec4(radiance, 1.0);
}
