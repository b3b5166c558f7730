#version 450 core
// The radiance exchange of one direction (Sec. 4.2, Eq. 3) as one pass over the atlas texels: each
// receiver y finds its sender x in the k-buffer and adds L_y += (2 pi / N) f_r L_x cos theta, N applied
// when the sums are read (radiance.glsl). Sender and receiver atlases ping-pong (Sec. 5.5): this pass reads
// the sender atlases and writes sender + transfer into the receiver atlases, which are the next
// direction's senders, so the sender holds light of every order so far (interleaved light transfer).
// Both orientations of the direction serve: a receiver takes its sender on the side its face faces.
// GLOSSY: also writes the glossy transfer atlas for the next direction (Sec. 5.4). PUNCTUAL_LIGHTS: the
// glossy transfer includes the punctual lights' glossy reflection towards the next direction.
// AREA_GLOSSY: and the emitting triangles' glossy reflection, sampled as the frame's still frames do
// (lighting.glsl, areaSampleUnshadowed: 16 stratified points per triangle, the mesh's shadow cube at this
// frame's point), in place of the emitted light a bundle happens to bring (Fig. 11's hybrid carried over
// to the glossy transfer). Through the bundles, light -> glossy -> diffuse paths from a small emitter need
// w_i to hit the emitter and w_i+1 to fall in the lobe: on cornell-glossy a lamp's reflection off the tall
// block's top lay on the ceiling as blotches after thousands of directions.
#include "common/lighting.glsl"
#include "technique/grb/kbuffer.glsl"
#include "technique/grb/radiance.glsl"

uniform vec3 nextDir;           // w_i+1, for the glossy transfer atlas
#ifdef AREA_GLOSSY
uniform vec2 areaRotation;      // this direction's offset of the emitters' points
#endif

layout(location = 0) out vec4 outDirect;
layout(location = 1) out vec4 outIndirect;
#ifdef GLOSSY
layout(location = 2) out vec4 outGlossy;
#endif

void main()
{
    ivec2 y = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(atlasPosition, y, 0);
    if (pos.w == 0.0) discard; // not on any surface: stays zero in both atlases
    vec4 nrm = texelFetch(atlasNormal, y, 0);
    vec3 nf = unpackFaceNormal(nrm.w), ns = nrm.xyz;
    vec4 direct = texelFetch(senderDirect, y, 0), indirect = texelFetch(senderIndirect, y, 0);

    BundleSample s = bundleSender(pos.xyz, nf, ns, atlasChart(y));
    vec3 Le = vec3(0.0), Lr = vec3(0.0);
    uint self = atlasTexelIndex(y) + 1u;
    if (s.counts && s.sender != 0u && s.sender != self && s.cosine > 0.0)
        senderRadiance(atlasTexelOf(s.sender - 1u), -s.wi, Le, Lr);

    uint material = uint(pos.w) - 1u;
    BrdfParams b = atlasBrdf(y, material);
    // Eq. 3 with p = 1 / (2 pi) and f_r's diffuse part c_diff t(cos_i) t(cos_o) / pi, c_diff and
    // t(cos_o) left to the reader: 2 pi / pi t(cos_i) cos_i L.
    vec3 weight = 2.0 * s.cosine * brdfTransmission(b, s.cosine);
    float counted = s.counts ? 1.0 : 0.0;
    outDirect = direct + vec4(weight * Le, counted);
    outIndirect = indirect + vec4(weight * Lr, counted);
#ifdef GLOSSY
    // Sec. 5.4: L_x f_r(y, w_i, w_i+1) cos theta for the next direction, on the side y faces.
    vec3 wo = dot(nf, nextDir) >= 0.0 ? nextDir : -nextDir;
#ifdef INTERLEAVED
    vec3 reflected = Lr; // light of every order so far
#else
    vec3 reflected = vec3(0.0); // one bounce: the lobe reflects direct light only
#endif
    vec3 glossy = vec3(0.0);
    if (b.weight > 0.0 && dot(ns, wo) > 0.0) {
#ifdef AREA_GLOSSY
        glossy = 2.0 * kPi * brdfGlossy(b, ns, wo, s.wi) * reflected * s.cosine;
#else
        glossy = 2.0 * kPi * brdfGlossy(b, ns, wo, s.wi) * (Le + reflected) * s.cosine;
#endif
        // The lights' glossy reflection by the frame's estimators (lighting.glsl), the lobe alone: the
        // diffuse part is the bundles'. The emitters first, as the sums have always been taken.
        BrdfParams lobe = b;
        lobe.diffuse = vec3(0.0);
#ifdef AREA_GLOSSY
        glossy += sampledAreaLights(punctualLightCount, lightCount, pos.xyz, ns, wo, lobe, areaRotation);
#endif
#ifdef PUNCTUAL_LIGHTS
        for (int i = 0; i < punctualLightCount; ++i) glossy += directFromPunctual(frameLight(i), pos.xyz, ns, wo, lobe);
#endif
    }
    outGlossy = vec4(glossy, 1.0);
#endif
}
