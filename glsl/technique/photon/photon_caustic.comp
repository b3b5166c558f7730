#version 450 core
// The caustic photon map read at every pixel (Jensen 2001; the paper's section 3.1 keeps caustic photons
// apart): the caustic photons (L S+ D, photon_trace.comp: incoming.w = 1) within `radius` of the pixel's
// surface point and facing its normal, each weighted by a cone filter (Jensen's k = 1, w = 1 - d / r,
// normalised by 1 - 2 / 3k) and reflected by the diffuse part of the BRDF, added to the pixel's indirect
// light. The photons are found in the photon tree, which holds every photon: a walk of the subtrees whose
// boxes come within the radius. Only the diffuse lobe reads them: a near-specular surface's caustics are
// what its sampled glossy bounce sees (photon_glossy.comp), and the final gather leaves the paths out that
// this map carries (photon_gather.glsl: no near-specular reflection of the lights at its hits).
#include "common/gbuffer.glsl"
#include "technique/photon/density.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform image2D target;

uniform ivec2 viewport;
uniform vec3 cameraPosition;
uniform float radius; // scene units

void main()
{
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(q, viewport))) return;
    GSurface g = gbufferSurface(q);
    if (!g.geometry) return;
    BrdfParams b = gbufferBrdf(q);
    vec3 x = g.position, n = g.normal;
    vec3 wo = normalize(cameraPosition - x);
    float r2 = radius * radius;
    vec3 sum = vec3(0.0);
    uint i = max(b.diffuse.r, max(b.diffuse.g, b.diffuse.b)) > 0.0 ? 1u : 0u;
    while (i != 0u) {
        PhotonNode node = photonNodes[i];
        if (node.lo.w <= 0.0 || boxDistance2(x, node.lo.xyz, node.hi.xyz) > r2) {
            i = skipSubtree(i);
        } else if (!nodeIsLeaf(i)) {
            i = 2u * i;
        } else {
            uvec2 range = nodeRange(i);
            for (uint p = range.x; p < range.y; ++p) {
                Photon ph = photons[p];
                vec3 d = ph.positionPath.xyz - x;
                float dd = dot(d, d);
                if (ph.incoming.w > 0.5 && dd < r2 && dot(ph.normal.xyz, n) > 0.1) {
                    vec3 diffuseFactor, glossy;
                    brdfEvalLobes(b, n, wo, ph.incoming.xyz, diffuseFactor, glossy);
                    sum += diffuseFactor * ph.powerIndex.rgb * (1.0 - sqrt(dd) / radius);
                }
            }
            i = skipSubtree(i);
        }
    }
    // The cone filter's normalisation for k = 1: 1 - 2 / 3 = 1 / 3.
    vec3 radiance = b.diffuse * sum * (3.0 / (kPi * r2));
    vec4 before = imageLoad(target, q);
    imageStore(target, q, vec4(before.rgb + radiance, before.a));
}
