#version 450 core
// The final glossy bounce (Sec. 5.3): at every G-buffer pixel with a glossy lobe, Eq. 3 towards the eye
// (w_i+1 = w_o) for this direction, from the sender the pixel finds in the k-buffer, added (blending) to a
// per-pixel sum with the count in alpha. Light the sender emits is left out: the frame's direct light
// holds its glossy reflection.
#include "common/gbuffer.glsl"
#include "technique/grb/kbuffer.glsl"
#include "technique/grb/radiance.glsl"

uniform vec3 cameraPosition;

layout(location = 0) out vec4 outGlossy;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(gPosition, px, 0);
    vec4 diff = texelFetch(gDiffuse, px, 0);
    if (pos.w == 0.0 || diff.a <= 0.0) discard;
    vec3 n = texelFetch(gNormal, px, 0).xyz;
    vec4 spec = texelFetch(gSpecular, px, 0);
    BrdfParams b;
    b.diffuse = diff.rgb;
    b.weight = diff.a;
    b.f0 = spec.rgb;
    b.alpha = max(spec.a * spec.a, 1e-3);
    vec3 wo = normalize(cameraPosition - pos.xyz);
    BundleSample s = bundleSender(pos.xyz, n, n, 0u); // a pixel has no chart: the nearest depth decides
    vec3 glossy = vec3(0.0);
    if (s.counts && s.sender != 0u && s.cosine > 0.0) {
        vec3 Le, Lr;
        senderRadiance(atlasTexelOf(s.sender - 1u), -s.wi, Le, Lr);
        glossy = 2.0 * kPi * brdfGlossy(b, n, wo, s.wi) * Lr * s.cosine;
    }
    outGlossy = vec4(glossy, s.counts ? 1.0 : 0.0);
}
