// The radiance atlases of global ray-bundles (Sec. 5) and the radiance a sender sends.
//
// What is stored, per atlas texel y (all RGBA32F, the count of directions that sampled y in alpha):
//   seed:     E_p / pi, the diffuse irradiance from point, spot and directional lights over pi, through
//             the frame's shadow maps (the paper's Fig. 11 hybrid), each light's cosine through the
//             BRDF's Fresnel transmission (brdfTransmission);
//   direct:   the sum over directions of Eq. 3 without the receiver's albedo, for light emitted by the
//             sender: 2 pi / pi t(cos) L_e(x) cos = 2 t(cos) L_e(x) cos; divided by the count it is
//             the light from emitting surfaces, carried by the bundles (Sec. 5.1);
//   indirect: the same for everything else the sender sends (Sec. 5.2, 5.5): what the frame does not
//             compute, the only part shown (display.frag);
//   glossy:   the glossy transfer atlas (Sec. 5.4), 2 pi f_g(y, w_i, w_i+1) L(x) cos for the next
//             direction w_i+1 (plus the glossy reflection of the punctual lights towards it).
// The albedo is left out so that textures stay sharp where the display multiplies by the G-buffer's.
// A diffuse sender x sends, towards direction wo, c_diff t(n.wo) (seed + (direct + indirect) / count):
// the Fresnel transmission on the way in is in the stored sums, on the way out it is applied here.
#ifndef BOUNCE_GRB_RADIANCE_GLSL
#define BOUNCE_GRB_RADIANCE_GLSL

#include "common/brdf.glsl"
#include "common/scene.glsl"
#include "common/material.glsl"
#include "technique/grb/atlas.glsl"

layout(binding = UNIT_GRB_SEED) uniform sampler2D seedAtlas;
layout(binding = UNIT_GRB_SENDER_DIRECT) uniform sampler2D senderDirect;
layout(binding = UNIT_GRB_SENDER_INDIRECT) uniform sampler2D senderIndirect;
#ifdef GLOSSY
layout(binding = UNIT_GRB_SENDER_GLOSSY) uniform sampler2D senderGlossy;
#endif

// The BRDF of atlas texel t (material from the position atlas's w, base colour from its atlas).
BrdfParams atlasBrdf(ivec2 t, uint material)
{
    return materialBrdf(materials[material], texelFetch(atlasBaseColor, t, 0).rgb);
}

// The per-albedo diffuse radiance stored at t: seed + accumulated, each sum over its own count.
vec3 atlasDiffuseSum(ivec2 t)
{
    vec4 d = texelFetch(senderDirect, t, 0), i = texelFetch(senderIndirect, t, 0);
    return texelFetch(seedAtlas, t, 0).rgb + (d.rgb + i.rgb) / max(d.a, 1.0);
}

// What sender texel x sends towards wo: emitted (Le) and reflected (Lr) radiance apart, so that light
// from emitters (direct light at the receiver, which the frame computes) stays apart from the rest.
// Nothing when x turns its back to wo (back faces are black and opaque).
void senderRadiance(ivec2 x, vec3 wo, out vec3 Le, out vec3 Lr)
{
    Le = vec3(0.0);
    Lr = vec3(0.0);
    vec4 pos = texelFetch(atlasPosition, x, 0);
    vec4 nrm = texelFetch(atlasNormal, x, 0);
    if (pos.w == 0.0 || dot(unpackFaceNormal(nrm.w), wo) <= 0.0) return;
    uint material = uint(pos.w) - 1u;
    BrdfParams b = atlasBrdf(x, material);
    Le = materials[material].emissionRoughness.rgb;
#ifdef INTERLEAVED
    Lr = b.diffuse * brdfTransmission(b, max(dot(nrm.xyz, wo), 0.0)) * atlasDiffuseSum(x);
#ifdef GLOSSY
    Lr += texelFetch(senderGlossy, x, 0).rgb; // prepared for this direction at the previous one (Sec. 5.4)
#endif
#else
    // One bounce only (Sec. 5.2 before 5.5): senders send the seeded direct light, nothing gathered; a
    // glossy sender also its lobe's reflection of the direct light (transfer.frag keeps the rest out).
    Lr = b.diffuse * brdfTransmission(b, max(dot(nrm.xyz, wo), 0.0)) * texelFetch(seedAtlas, x, 0).rgb;
#ifdef GLOSSY
    Lr += texelFetch(senderGlossy, x, 0).rgb; // its direct light alone in this mode
#endif
#endif
}

#endif
