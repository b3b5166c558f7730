// The one BRDF of Bounce. glsl/common/brdf.glsl is its GLSL twin; the two are tested against each other,
// so a change here is a change there.
//
// Lambertian diffuse plus one GGX microfacet lobe, mixed by a Schlick Fresnel term:
//   c_diff = baseColor (1 - metallic)
//   F0     = mix(min(0.04 specularColor, 1), baseColor, metallic)     per channel
//   w      = mix(specular, 1, metallic)                                the specular weight
//   alpha  = max(roughness^2, 1e-3)
// For unit n, wo (towards the viewer) and wi (towards the light), with n.wo > 0 and n.wi > 0 (else f = 0):
//   h   = normalize(wo + wi)
//   F   = F0 + (1 - F0) (1 - max(wo.h, 0))^5                           (Schlick 1994)
//   D   = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2)                 (GGX, Walter et al. 2007, Eq. 33)
//   Vis = 0.5 / (n.wi sqrt((n.wo)^2 (1 - alpha^2) + alpha^2) + n.wo sqrt((n.wi)^2 (1 - alpha^2) + alpha^2))
//         the height-correlated Smith term G2 / (4 n.wi n.wo)          (Heitz 2014, Eq. 99)
//   Fo  = F0 + (1 - F0) (1 - n.wo)^5,  Fi = F0 + (1 - F0) (1 - n.wi)^5
//   f   = (1 - w Fo) (1 - w Fi) c_diff / pi + w F D Vis                per RGB channel, without the cosine
// Precision: evaluated in float exactly as written (the GLSL twin must agree to 1e-5), the denominator
// of D cancels 1 - (n.h)^2 near the peak of smooth lobes: at alpha = 1e-3 (roughness <= 0.03) D is off by
// up to ~10% there, at roughness 0.1 by ~1e-4. Both twins share the error, and evalBrdf and pdfBrdf compute
// h and D identically so that D cancels in f / pdf. Rewriting the denominator as
// |n x h|^2 + alpha^2 (n.h)^2 (the same expression) removes it; it must then change in both twins at once.
// f is reciprocal (wo.h == wi.h, and the diffuse weight is symmetric in wo and wi). The diffuse part is
// weighted by what the interface transmits in and out, so that at grazing wo, where the glossy lobe
// reflects nearly everything, the diffuse part vanishes: a white dielectric (metallic 0, specular 1,
// baseColor 1) reflects at most what it receives at every angle (brdf_test.cpp's white furnace). The
// weight 1 - w F(wo.h) of a per-sample mix would not: it leaves the diffuse part whole at grazing wo and
// reflects up to 1.8 times the incident energy there.
//
// Sampling mixes two strategies, chosen per sample with the probability pSpecular (specularProbability):
// cosine-weighted hemisphere sampling for the diffuse part and sampling of the GGX distribution of
// visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4)) for the
// glossy part. pdf() is the density of that mixture over the whole sphere of directions: the visible-
// normal strategy can reflect below the horizon, where f = 0 but the density is not, so the mixture
// integrates to 1 over the sphere and to at most 1 over the upper hemisphere. Lambertian materials
// (w == 0: specular 0 and metallic 0) have pSpecular = 0: pure cosine sampling.
#pragma once

#include <glm/glm.hpp>

#include "core/scene.h"

namespace bounce::core {

struct BrdfParams {
    glm::vec3 diffuse{0.0f}; // c_diff
    glm::vec3 f0{0.04f};
    float weight = 0.0f; // w, the specular weight
    float alpha = 1.0f;  // GGX alpha = max(roughness^2, 1e-3)

    // From a material; textureColor (linear RGB, the decoded baseColor texel) multiplies baseColor.
    static BrdfParams fromMaterial(const Material& m, const glm::vec3& textureColor = glm::vec3(1.0f));
    bool hasSpecular() const { return weight > 0.0f; }
    bool hasDiffuse() const { return diffuse.x > 0.0f || diffuse.y > 0.0f || diffuse.z > 0.0f; }
};

// f(wo, wi), without the cosine; zero unless both directions are above the surface (n.w > 0).
glm::vec3 evalBrdf(const BrdfParams& p, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi);

// The probability of choosing the glossy strategy for this wo: the lobes' approximate reflectances,
// w F(n.wo) for glossy and lum(c_diff) (1 - w lum F(n.wo)) for diffuse, normalised and kept inside
// [0.1, 0.9] when both lobes exist (so neither strategy starves where the estimate is poor); exactly 0
// without a glossy lobe and exactly 1 without a diffuse one.
float specularProbability(const BrdfParams& p, const glm::vec3& n, const glm::vec3& wo);

struct BrdfSample {
    glm::vec3 wi{0.0f};
    float pdf = 0.0f;   // solid-angle density of the mixture at wi (pdfBrdf(n, wo, wi))
    glm::vec3 f{0.0f};  // evalBrdf(n, wo, wi): zero when wi is below the surface
    bool valid = false; // false when no direction could be produced (wo below the surface)
};

// Draws wi from the mixture; u1 chooses the strategy, (u2, u3) warp the direction.
BrdfSample sampleBrdf(const BrdfParams& p, const glm::vec3& n, const glm::vec3& wo, float u1, float u2, float u3);

// The mixture density: (1 - pSpecular) cos/pi [n.wi > 0] + pSpecular D_wo(h) / (4 wo.h), where D_wo is the
// visible-normal density (Heitz 2018, Eq. 1 and 17): D_wo(h) / (4 wo.h) = G1(wo) D(h) / (4 n.wo).
// Zero when n.wo <= 0.
float pdfBrdf(const BrdfParams& p, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi);

// The separate terms, for tests and for the GLSL comparison.
float ggxD(float nDotH, float alpha);
float smithVisibility(float nDotWi, float nDotWo, float alpha); // Vis = G2 / (4 n.wi n.wo)
float smithG1(float nDotW, float alpha);
glm::vec3 fresnelSchlick(const glm::vec3& f0, float cosTheta);
float luminance(const glm::vec3& rgb); // Rec. 709 / sRGB primaries: 0.2126 R + 0.7152 G + 0.0722 B

} // namespace bounce::core
