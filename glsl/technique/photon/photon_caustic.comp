#version 450 core
// The caustic photon map read at every pixel (Jensen 2001; the paper's section 3.1 keeps caustic photons
// apart): the caustic photons (L S+ D, photon_trace.comp: incoming.w = 1) within `radius` of the pixel's
// surface point and facing its normal, each weighted by a cone filter (Jensen's k = 1, w = 1 - d / r,
// normalised by 1 - 2 / 3k) and reflected by the diffuse part of the BRDF, added to the pixel's indirect
// light. The photons are found in the photon tree, which holds every photon: a walk of the subtrees whose
// boxes come within the radius. Only the diffuse lobe reads them: a near-specular surface's caustics are
// what its sampled glossy bounce sees (photon_glossy.comp), and the final gather leaves the paths out that
// this map carries (photon_gather.glsl: no near-specular reflection of the lights at its hits).
#include "technique/photon/pixel_pass.glsl"
#include "technique/photon/density.glsl"

uniform float radius; // scene units

// The caustic photons' light at x (shading normal n) reflected towards wo by the diffuse lobe of b.
vec3 causticRadiance(vec3 x, vec3 n, vec3 wo, BrdfParams b)
{
    float r2 = radius * radius;
    vec3 sum = vec3(0.0);
    uint i = max(b.diffuse.r, max(b.diffuse.g, b.diffuse.b)) > 0.0 ? 1u : 0u;
    while (i != 0u) {
        if (!walkToLeafNear(i, x, r2)) continue;
        uvec2 range = nodeRange(i);
        for (uint p = range.x; p < range.y; ++p) {
            Photon ph = photons[p];
            float dd = photonDistance2(ph, x);
            if (ph.incoming.w > 0.5 && dd < r2 && dot(ph.normal.xyz, n) > 0.1) {
                vec3 diffuseFactor, glossy;
                brdfEvalLobes(b, n, wo, ph.incoming.xyz, diffuseFactor, glossy);
                sum += diffuseFactor * ph.powerIndex.rgb * (1.0 - sqrt(dd) / radius);
            }
        }
        i = skipSubtree(i);
    }
    // The cone filter's normalisation for k = 1: 1 - 2 / 3 = 1 / 3.
    return b.diffuse * sum * (3.0 / (kPi * r2));
}

void main()
{
    PixelPoint s;
    if (loadPixelPoint(s)) addToPixel(s.q, causticRadiance(s.x, s.n, s.wo, s.b));
}
