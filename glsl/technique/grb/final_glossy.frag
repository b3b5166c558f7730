#version 450 core
// The final glossy bounce (Sec. 5.3): at every G-buffer pixel with a glossy lobe, Eq. 3 towards the eye
// (w_i+1 = w_o) for this direction, from the sender the pixel finds in the k-buffer, added (blending) to a
// per-pixel sum with the count in alpha. Light the sender emits is left out (the frame's direct light
// holds its glossy reflection) unless SHOW_EMITTED (emitters=bundles: the frame leaves emitters out).
#include "common/gbuffer.glsl"
#include "technique/grb/kbuffer.glsl"
#include "technique/grb/radiance.glsl"

uniform vec3 cameraPosition;

layout(location = 0) out vec4 outGlossy;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    GSurface g = gbufferSurface(px);
    BrdfParams b = gbufferBrdf(px);
    if (!g.geometry || b.weight <= 0.0) discard;
    vec3 n = g.normal;
    vec3 wo = normalize(cameraPosition - g.position);
    BundleSample s = bundleSender(g.position, n, n, 0u); // a pixel has no chart: the nearest depth decides
    vec3 glossy = vec3(0.0);
    if (s.counts && s.sender != 0u && s.cosine > 0.0) {
        vec3 Le, Lr;
        senderRadiance(atlasTexelOf(s.sender - 1u), -s.wi, Le, Lr);
#ifdef SHOW_EMITTED
        Lr += Le;
#endif
        glossy = 2.0 * kPi * brdfGlossy(b, n, wo, s.wi) * Lr * s.cosine;
    }
    outGlossy = vec4(glossy, s.counts ? 1.0 : 0.0);
}
