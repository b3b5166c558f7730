#include "core/brdf.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"

namespace bounce::core {

namespace {

constexpr float kInvPi = 0.31830988618379067f;

float pow5(float x)
{
    const float x2 = x * x;
    return x2 * x2 * x;
}

// Heitz 2018, Listing 1 (isotropic alpha): sample a normal visible from ve (local frame, z up, ve.z > 0).
glm::vec3 sampleVisibleNormal(const glm::vec3& ve, float alpha, float u1, float u2)
{
    // Stretch the view direction into the configuration where the microsurface is a hemisphere.
    const glm::vec3 vh = glm::normalize(glm::vec3(alpha * ve.x, alpha * ve.y, ve.z));
    // An orthonormal basis around vh; the first axis is horizontal (undefined, so any, at normal view).
    const float lenSq = vh.x * vh.x + vh.y * vh.y;
    const glm::vec3 t1 = lenSq > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lenSq) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 t2 = glm::cross(vh, t1);
    // A uniform point on the projected disk, warped towards the visible half (Section 4.2).
    const float r = std::sqrt(u1);
    const float phi = 2.0f * kPi * u2;
    const float p1 = r * std::cos(phi);
    float p2 = r * std::sin(phi);
    const float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
    // Reproject onto the hemisphere and unstretch.
    const glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
}

// The half vector, computed the same way wherever it is needed (as glsl/common/brdf.glsl does), so that
// D comes out bit-identical in evalBrdf and pdfBrdf and cancels exactly in f / pdf.
bool halfVector(const glm::vec3& wo, const glm::vec3& wi, glm::vec3& h)
{
    const glm::vec3 sum = wo + wi;
    if (!(glm::dot(sum, sum) > 1e-14f)) return false;
    h = glm::normalize(sum);
    return true;
}

// The visible-normal density of the reflected direction, G1(wo) D(h) / (4 n.wo), written with G1 of GGX
// (Heitz 2014, Eq. 86) so that n.wo cancels: D / (2 (n.wo + sqrt(alpha^2 + (1 - alpha^2) n.wo^2))).
float pdfSpecular(const BrdfParams& p, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi, float nDotWo)
{
    glm::vec3 h;
    // Visible normals lie above the surface: no density where h is below it (wi far below the horizon).
    if (!halfVector(wo, wi, h) || glm::dot(wo, h) <= 0.0f || glm::dot(n, h) <= 0.0f) return 0.0f;
    const float a2 = p.alpha * p.alpha;
    return ggxD(std::max(glm::dot(n, h), 0.0f), p.alpha) /
           (2.0f * (nDotWo + std::sqrt(a2 + (1.0f - a2) * nDotWo * nDotWo)));
}

} // namespace

float luminance(const glm::vec3& rgb)
{
    return 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z;
}

BrdfParams BrdfParams::fromMaterial(const Material& m, const glm::vec3& textureColor)
{
    const glm::vec3 base = m.baseColor * textureColor;
    BrdfParams p;
    p.diffuse = base * (1.0f - m.metallic);
    p.f0 = glm::mix(glm::min(0.04f * m.specularColor, glm::vec3(1.0f)), base, m.metallic);
    p.weight = glm::mix(m.specular, 1.0f, m.metallic);
    p.alpha = std::max(m.roughness * m.roughness, 1e-3f);
    return p;
}

float ggxD(float nDotH, float alpha)
{
    const float a2 = alpha * alpha;
    const float d = nDotH * nDotH * (a2 - 1.0f) + 1.0f;
    return a2 / (kPi * d * d);
}

float smithVisibility(float nDotWi, float nDotWo, float alpha)
{
    const float a2 = alpha * alpha;
    const float gv = nDotWi * std::sqrt(nDotWo * nDotWo * (1.0f - a2) + a2);
    const float gl = nDotWo * std::sqrt(nDotWi * nDotWi * (1.0f - a2) + a2);
    return 0.5f / (gv + gl);
}

float smithG1(float nDotW, float alpha)
{
    if (nDotW <= 0.0f) return 0.0f;
    const float a2 = alpha * alpha;
    return 2.0f * nDotW / (nDotW + std::sqrt(a2 + (1.0f - a2) * nDotW * nDotW));
}

glm::vec3 fresnelSchlick(const glm::vec3& f0, float cosTheta)
{
    return f0 + (1.0f - f0) * pow5(1.0f - std::max(cosTheta, 0.0f));
}

glm::vec3 evalBrdf(const BrdfParams& p, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi)
{
    const float nDotWi = glm::dot(n, wi);
    const float nDotWo = glm::dot(n, wo);
    if (nDotWi <= 0.0f || nDotWo <= 0.0f) return glm::vec3(0.0f);
    if (!p.hasSpecular()) return p.diffuse * kInvPi; // w = 0: the formula without its glossy terms
    glm::vec3 h;
    if (!halfVector(wo, wi, h)) return glm::vec3(0.0f); // wi == -wo cannot be above the surface with wo
    const glm::vec3 wF = p.weight * fresnelSchlick(p.f0, glm::dot(wo, h));
    // The diffuse part keeps what the glossy interface transmits on the way in and on the way out.
    const glm::vec3 transmitted =
        (1.0f - p.weight * fresnelSchlick(p.f0, nDotWo)) * (1.0f - p.weight * fresnelSchlick(p.f0, nDotWi));
    const glm::vec3 diffuse = transmitted * p.diffuse * kInvPi;
    return diffuse + wF * (ggxD(std::max(glm::dot(n, h), 0.0f), p.alpha) * smithVisibility(nDotWi, nDotWo, p.alpha));
}

float specularProbability(const BrdfParams& p, const glm::vec3& n, const glm::vec3& wo)
{
    if (!p.hasSpecular()) return 0.0f;
    if (!p.hasDiffuse()) return 1.0f;
    const float wF = p.weight * luminance(fresnelSchlick(p.f0, glm::dot(n, wo)));
    const float diffuse = luminance(p.diffuse) * std::max(0.0f, 1.0f - wF);
    const float sum = wF + diffuse;
    const float prob = sum > 0.0f ? wF / sum : 0.5f;
    return std::clamp(prob, 0.1f, 0.9f);
}

float pdfBrdf(const BrdfParams& p, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi)
{
    const float nDotWo = glm::dot(n, wo);
    if (nDotWo <= 0.0f) return 0.0f;
    const float pSpec = specularProbability(p, n, wo);
    float pdf = 0.0f;
    if (pSpec < 1.0f) pdf += (1.0f - pSpec) * cosineHemispherePdf(glm::dot(n, wi));
    if (pSpec > 0.0f) pdf += pSpec * pdfSpecular(p, n, wo, wi, nDotWo);
    return pdf;
}

BrdfSample sampleBrdf(const BrdfParams& p, const glm::vec3& n, const glm::vec3& wo, float u1, float u2, float u3)
{
    BrdfSample s;
    const float nDotWo = glm::dot(n, wo);
    if (nDotWo <= 0.0f) return s;
    const Frame frame = Frame::fromNormal(n);
    if (!p.hasSpecular()) {
        // Lambertian: pure cosine sampling, pdf cos/pi, f = c_diff/pi (the general path gives the same).
        s.wi = glm::normalize(frame.toWorld(sampleCosineHemisphere({u2, u3})));
        const float c = glm::dot(n, s.wi);
        s.pdf = cosineHemispherePdf(c);
        s.f = c > 0.0f ? p.diffuse * kInvPi : glm::vec3(0.0f);
        s.valid = s.pdf > 0.0f;
        return s;
    }
    const float pSpec = specularProbability(p, n, wo);
    if (u1 < pSpec) {
        const glm::vec3 woLocal = frame.toLocal(wo);
        const glm::vec3 hLocal = sampleVisibleNormal(glm::normalize(woLocal), p.alpha, u2, u3);
        const glm::vec3 h = frame.toWorld(hLocal);
        s.wi = glm::normalize(2.0f * glm::dot(wo, h) * h - wo);
    } else {
        s.wi = glm::normalize(frame.toWorld(sampleCosineHemisphere({u2, u3})));
    }
    s.pdf = pdfBrdf(p, n, wo, s.wi);
    s.f = evalBrdf(p, n, wo, s.wi);
    s.valid = s.pdf > 0.0f;
    return s;
}

} // namespace bounce::core
