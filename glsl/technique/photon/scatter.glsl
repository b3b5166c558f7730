// Sampling the one BRDF (common/brdf.glsl) for photon scattering, as core/brdf.cpp samples it for the
// path tracer: cosine-weighted directions for the diffuse part, GGX visible normals (Heitz 2018) for the
// glossy part, mixed with core::specularProbability's weights. The BRDF is reciprocal, so a photon
// arriving from wo leaves along wi with weight f(wo, wi) (n.wi) / pdf(wi).
#ifndef BOUNCE_PHOTON_SCATTER_GLSL
#define BOUNCE_PHOTON_SCATTER_GLSL

#include "common/brdf.glsl"

// Duff et al. 2017: an orthonormal basis around n.
void basisAround(vec3 n, out vec3 t, out vec3 b)
{
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

vec3 cosineDirection(vec3 n, vec2 u)
{
    // Malley: a concentric disk point lifted to the hemisphere (Shirley & Chiu 1997).
    vec2 o = 2.0 * u - 1.0;
    vec2 d = vec2(0.0);
    if (o.x != 0.0 || o.y != 0.0) {
        float r, theta;
        if (abs(o.x) > abs(o.y)) {
            r = o.x;
            theta = 0.25 * kPi * (o.y / o.x);
        } else {
            r = o.y;
            theta = 0.5 * kPi - 0.25 * kPi * (o.x / o.y);
        }
        d = r * vec2(cos(theta), sin(theta));
    }
    vec3 t, b;
    basisAround(n, t, b);
    float z = sqrt(max(0.0, 1.0 - dot(d, d)));
    return normalize(d.x * t + d.y * b + z * n);
}

float fresnelLuminance(BrdfParams p, float cosTheta)
{
    vec3 f = p.f0 + (1.0 - p.f0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
    return dot(f, vec3(0.2126, 0.7152, 0.0722));
}

bool brdfHasDiffuse(BrdfParams p)
{
    return max(p.diffuse.r, max(p.diffuse.g, p.diffuse.b)) > 0.0;
}

// core::specularProbability.
float specularProbability(BrdfParams p, vec3 n, vec3 wo)
{
    if (p.weight <= 0.0) return 0.0;
    if (!brdfHasDiffuse(p)) return 1.0;
    float wF = p.weight * fresnelLuminance(p, dot(n, wo));
    float diffuse = dot(p.diffuse, vec3(0.2126, 0.7152, 0.0722)) * max(0.0, 1.0 - wF);
    float sum = wF + diffuse;
    return clamp(sum > 0.0 ? wF / sum : 0.5, 0.1, 0.9);
}

// Heitz 2018, Listing 1 (core/brdf.cpp: sampleVisibleNormal), in the local frame (z up).
vec3 sampleVisibleNormal(vec3 ve, float alpha, vec2 u)
{
    vec3 vh = normalize(vec3(alpha * ve.x, alpha * ve.y, ve.z));
    float lenSq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lenSq > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lenSq) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u.x);
    float phi = 2.0 * kPi * u.y;
    float p1 = r * cos(phi);
    float p2 = r * sin(phi);
    float s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * p2;
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return normalize(vec3(alpha * nh.x, alpha * nh.y, max(1e-6, nh.z)));
}

// The solid-angle density of a reflected direction drawn by sampleVisibleNormal:
// D(h) G1(wo) / (4 n.wo) with Smith's G1 = 2 n.wo / (n.wo + sqrt(alpha^2 + (1 - alpha^2) (n.wo)^2)).
float visibleNormalPdf(float alpha, float nDotH, float nDotWo)
{
    float a2 = alpha * alpha;
    return ggxD(max(nDotH, 0.0), a2) / (2.0 * (nDotWo + sqrt(a2 + (1.0 - a2) * nDotWo * nDotWo)));
}

// Draws wi from the glossy lobe alone (its visible normals, seen from wo); returns f_glossy (n.wi) / pdf
// with pdf brdfPdf's glossy term, 0 where wi falls below the surface.
vec3 sampleGlossyLobe(BrdfParams b, vec3 n, vec3 wo, vec2 u, out vec3 wi)
{
    vec3 t, bt;
    basisAround(n, t, bt);
    vec3 hl = sampleVisibleNormal(normalize(vec3(dot(wo, t), dot(wo, bt), dot(wo, n))), b.alpha, u);
    wi = reflect(-wo, hl.x * t + hl.y * bt + hl.z * n);
    float nDotWi = dot(n, wi);
    if (nDotWi <= 0.0) return vec3(0.0);
    float pdf = visibleNormalPdf(b.alpha, dot(n, normalize(wo + wi)), dot(n, wo));
    return pdf > 0.0 ? brdfGlossy(b, n, wo, wi) * (nDotWi / pdf) : vec3(0.0);
}

// core::pdfBrdf: the mixture's solid-angle density of wi.
float brdfPdf(BrdfParams p, vec3 n, vec3 wo, vec3 wi)
{
    float nDotWo = dot(n, wo);
    if (nDotWo <= 0.0) return 0.0;
    float pSpec = specularProbability(p, n, wo);
    float pdf = 0.0;
    if (pSpec < 1.0) pdf += (1.0 - pSpec) * max(dot(n, wi), 0.0) / kPi;
    if (pSpec > 0.0) {
        vec3 sum = wo + wi;
        if (dot(sum, sum) > 1e-14) {
            vec3 h = normalize(sum);
            if (dot(wo, h) > 0.0 && dot(n, h) > 0.0) pdf += pSpec * visibleNormalPdf(p.alpha, dot(n, h), nDotWo);
        }
    }
    return pdf;
}

// Draws wi for a photon arriving from wo; returns f (n.wi) / pdf (zero when no direction is valid).
vec3 scatterPhoton(BrdfParams p, vec3 n, vec3 wo, float u1, vec2 u, out vec3 wi)
{
    wi = n;
    if (dot(n, wo) <= 0.0) return vec3(0.0);
    float pSpec = specularProbability(p, n, wo);
    if (u1 < pSpec) {
        vec3 t, b;
        basisAround(n, t, b);
        vec3 woLocal = normalize(vec3(dot(wo, t), dot(wo, b), dot(wo, n)));
        vec3 hl = sampleVisibleNormal(woLocal, p.alpha, u);
        vec3 h = hl.x * t + hl.y * b + hl.z * n;
        wi = normalize(2.0 * dot(wo, h) * h - wo);
    } else {
        wi = cosineDirection(n, u);
    }
    float pdf = brdfPdf(p, n, wo, wi);
    if (!(pdf > 0.0)) return vec3(0.0);
    return brdfEval(p, n, wo, wi) * (max(dot(n, wi), 0.0) / pdf);
}

#endif
