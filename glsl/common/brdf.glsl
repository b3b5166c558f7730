// The one BRDF of Bounce, the GLSL twin of core/brdf.h (tested against it to 1e-5 relative):
// Lambertian diffuse baseColor (1 - metallic) plus one GGX lobe (height-correlated Smith, Schlick).
//   F0 = mix(min(0.04 specularColor, 1), baseColor, metallic), w = mix(specular, 1, metallic)
//   f  = (1 - w F) c_diff / pi + w F D Vis
// SCENE_DIFFUSE_ONLY (gl/frame/frame.h: Frame::gbufferDefines): no material of the scene has a glossy lobe
// (w = 0 everywhere), so the glossy terms are compiled out: a SIMD rasteriser (llvmpipe) evaluates both
// sides of the w <= 0 test, GGX included, for every pixel.
#ifndef BOUNCE_BRDF_GLSL
#define BOUNCE_BRDF_GLSL

const float kPi = 3.14159265358979323846;
const vec3 kLuminance = vec3(0.2126, 0.7152, 0.0722); // Rec. 709 weights of linear RGB

struct BrdfParams {
    vec3 diffuse;    // c_diff = baseColor (1 - metallic)
    vec3 f0;
    float weight;    // w, the specular weight
    float alpha;     // roughness^2, at least 1e-3
};

BrdfParams brdfParams(vec3 baseColor, float metallic, float roughness, float specular, vec3 specularColor)
{
    BrdfParams p;
    p.diffuse = baseColor * (1.0 - metallic);
    p.f0 = mix(min(0.04 * specularColor, vec3(1.0)), baseColor, metallic);
    p.weight = mix(specular, 1.0, metallic);
    p.alpha = max(roughness * roughness, 1e-3);
    return p;
}

float ggxD(float NdotH, float a2)
{
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

// Height-correlated Smith visibility, G2 / (4 NdotL NdotV).
float smithVis(float NdotL, float NdotV, float a2)
{
    float gv = NdotL * sqrt(NdotV * NdotV * (1.0 - a2) + a2);
    float gl = NdotV * sqrt(NdotL * NdotL * (1.0 - a2) + a2);
    return 0.5 / (gv + gl);
}

// Schlick's 5th power of 1 - cos. pow of a negative base is undefined in GLSL (NaN on llvmpipe): a unit
// dot product may round to 1 + 1 ulp (a direction exactly along n), so 1 - cos is clamped at 0, where
// core/brdf.cpp's x^5 gives -1e-35. Three multiplications as there, not pow (exp2 of log2 in software).
float schlickWeight(float cosTheta)
{
    float m = max(1.0 - cosTheta, 0.0);
    float m2 = m * m;
    return m2 * m2 * m;
}

// What the glossy interface lets through to the diffuse part in one direction: 1 - w F(cos).
vec3 brdfTransmission(BrdfParams p, float cosTheta)
{
#ifdef SCENE_DIFFUSE_ONLY
    return vec3(1.0);
#else
    return 1.0 - p.weight * (p.f0 + (1.0 - p.f0) * schlickWeight(cosTheta));
#endif
}

// 1 - w F at the cosine-weighted mean of Schlick's weight over a hemisphere of directions, 2 int (1 - mu)^5 mu dmu
// = 1/21: what the interface lets through on one side of a light that reaches it (or leaves it) from every
// direction alike, where one radiance or irradiance stands for all of them (the point clouds' stored
// radiance, the irradiance probes of ddgi).
vec3 brdfMeanTransmission(BrdfParams p)
{
#ifdef SCENE_DIFFUSE_ONLY
    return vec3(1.0);
#else
    return 1.0 - p.weight * (p.f0 + (1.0 - p.f0) * (1.0 / 21.0));
#endif
}

// The glossy lobe alone, w F D Vis, without the cosine; zero below either horizon.
vec3 brdfGlossy(BrdfParams p, vec3 n, vec3 wo, vec3 wi)
{
#ifdef SCENE_DIFFUSE_ONLY
    return vec3(0.0);
#else
    float NdotL = dot(n, wi), NdotV = dot(n, wo);
    if (NdotL <= 0.0 || NdotV <= 0.0 || p.weight <= 0.0) return vec3(0.0);
    vec3 h = normalize(wo + wi);
    float VdotH = max(dot(wo, h), 0.0);
    vec3 F = p.f0 + (1.0 - p.f0) * schlickWeight(VdotH);
    float a2 = p.alpha * p.alpha;
    return p.weight * F * ggxD(max(dot(n, h), 0.0), a2) * smithVis(NdotL, NdotV, a2);
#endif
}

// The two lobes of f(wo, wi) apart, zero below either horizon: f = diffuseFactor c_diff + glossy, with
// diffuseFactor what the interface transmits in and out over pi (without the diffuse colour, which
// point-based gathers leave to the receiver's full-resolution G-buffer) and glossy = w F D Vis.
void brdfEvalLobes(BrdfParams p, vec3 n, vec3 wo, vec3 wi, out vec3 diffuseFactor, out vec3 glossy)
{
    diffuseFactor = vec3(0.0);
    glossy = vec3(0.0);
    float NdotL = dot(n, wi), NdotV = dot(n, wo);
    if (NdotL <= 0.0 || NdotV <= 0.0) return;
    diffuseFactor = brdfTransmission(p, NdotV) * brdfTransmission(p, NdotL) / kPi;
    glossy = brdfGlossy(p, n, wo, wi);
}

// f(wo, wi) without the cosine; zero below either horizon.
vec3 brdfEval(BrdfParams p, vec3 n, vec3 wo, vec3 wi)
{
    vec3 diffuseFactor, glossy;
    brdfEvalLobes(p, n, wo, wi, diffuseFactor, glossy);
    return diffuseFactor * p.diffuse + glossy;
}

#endif
