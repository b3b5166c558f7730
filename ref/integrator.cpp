#include "ref/integrator.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>

namespace bounce::ref {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// Russian roulette starts after this many reflections and never keeps a path with more than this
// probability, so every path ends with probability 1 (Arvo & Kirk 1990; the 1/q reweighting keeps it
// unbiased).
constexpr int kRouletteStart = 3;
constexpr float kRouletteMaxKeep = 0.95f;

// The power heuristic with beta = 2 (Veach 1997, Eq. 9.13), for one sample of each strategy.
float powerHeuristic(float pdfThis, float pdfOther)
{
    const float a = pdfThis * pdfThis, b = pdfOther * pdfOther;
    return a + b > 0.0f ? a / (a + b) : 0.0f;
}

bool isZero(const glm::vec3& v)
{
    return v.x == 0.0f && v.y == 0.0f && v.z == 0.0f;
}
float maxComponent(const glm::vec3& v)
{
    return std::max({v.x, v.y, v.z});
}

} // namespace

Integrator::Integrator(const EmbreeScene& geometry, const LightTable& lights, LightPaths paths, int maxDepth)
    : geometry_(geometry), lights_(lights)
{
    // The reflection counts each selection keeps; the no-visibility term (2 reflections) is separate.
    switch (paths) {
    case LightPaths::Direct:
        minReflections_ = 0;
        maxReflections_ = 1;
        break;
    case LightPaths::OneBounce:
        minReflections_ = 0;
        maxReflections_ = 2;
        break;
    case LightPaths::OneBounceIndirect:
        minReflections_ = 2;
        maxReflections_ = 2;
        break;
    case LightPaths::OneBounceNoVis:
        minReflections_ = 0;
        maxReflections_ = 1;
        noVisibility_ = true;
        break;
    case LightPaths::OneBounceNoVisIndirect:
        minReflections_ = 2;
        maxReflections_ = 1;
        noVisibility_ = true;
        break;
    case LightPaths::Full:
        minReflections_ = 0;
        maxReflections_ = maxDepth > 0 ? maxDepth : INT_MAX;
        russianRoulette_ = true;
        break;
    }
}

bool Integrator::shade(const Hit& hit, const glm::vec3& wo, Shading& s) const
{
    s.surface = geometry_.surface(hit);
    const core::Material& m = *s.surface.material;
    s.ng = s.surface.ng;
    s.n = s.surface.ns;
    if (glm::dot(s.ng, wo) <= 0.0f) {
        if (!m.doubleSided) return false;
        s.ng = -s.ng;
        s.n = -s.n;
    }
    s.brdf = core::BrdfParams::fromMaterial(m, geometry_.textureColor(m, s.surface.uv));
    s.reflects = s.brdf.hasDiffuse() || s.brdf.hasSpecular();
    return true;
}

float Integrator::brdfHitWeight(float pdfBrdf, const glm::vec3& from, const SurfacePoint& p) const
{
    const float pdfAreaLight = lights_.pdfArea(p.triangle);
    if (pdfAreaLight <= 0.0f) return 1.0f;
    const glm::vec3 d = p.p - from;
    const float dist2 = glm::dot(d, d);
    const float cosLight = std::abs(glm::dot(p.ng, d)) / std::sqrt(dist2);
    if (cosLight <= 0.0f) return 1.0f;
    return powerHeuristic(pdfBrdf, pdfAreaLight * dist2 / cosLight);
}

glm::vec3 Integrator::lightSample(const Shading& s, const glm::vec3& wo, core::Pcg32& rng, std::uint64_t& rays) const
{
    glm::vec3 sum(0.0f);
    const glm::vec3& p = s.surface.p;
    const glm::vec3 origin = EmbreeScene::offsetOrigin(p, s.ng);
    for (const core::Light& light : geometry_.scene().lights) {
        if (light.type == core::LightType::Directional) {
            const glm::vec3 wi = -light.direction;
            const float cosS = glm::dot(s.n, wi);
            if (cosS <= 0.0f || glm::dot(s.ng, wi) <= 0.0f) continue;
            const glm::vec3 f = core::evalBrdf(s.brdf, s.n, wo, wi);
            if (isZero(f) || geometry_.occluded(origin, wi, 0.0f, kInfinity, rays)) continue;
            sum += f * cosS * light.intensity; // irradiance E (W/m^2) times f cos
            continue;
        }
        // Point and spot: I / r^2 times the angular weight (glTF's spot falloff, a step for hard cones).
        const glm::vec3 toLight = light.position - p;
        const float dist2 = glm::dot(toLight, toLight);
        if (!(dist2 > 0.0f)) continue;
        const glm::vec3 wi = toLight / std::sqrt(dist2);
        const float cosS = glm::dot(s.n, wi);
        if (cosS <= 0.0f || glm::dot(s.ng, wi) <= 0.0f) continue;
        const float angular = light.spotWeight(glm::dot(-wi, light.direction));
        if (angular <= 0.0f) continue;
        const glm::vec3 f = core::evalBrdf(s.brdf, s.n, wo, wi);
        if (isZero(f)) continue;
        const glm::vec3 shadow = light.position - origin;
        const float shadowLen = glm::length(shadow);
        if (geometry_.occluded(origin, shadow / shadowLen, 0.0f, shadowLen * (1.0f - 1e-5f), rays)) continue;
        sum += f * (cosS * angular / dist2) * light.intensity;
    }

    // One point on the emissive triangles, weighted against BRDF sampling of the same direction.
    if (lights_.hasAreaLights()) {
        const float uSelect = rng.nextFloat();
        const glm::vec2 uTri = rng.next2();
        const AreaLightSample ls = lights_.sampleArea(uSelect, uTri);
        const glm::vec3 toLight = ls.p - p;
        const float dist2 = glm::dot(toLight, toLight);
        if (ls.pdfArea > 0.0f && dist2 > 0.0f) {
            const float dist = std::sqrt(dist2);
            const glm::vec3 wi = toLight / dist;
            const float cosFront = glm::dot(ls.ng, -wi);
            const bool emits = cosFront > 0.0f || (ls.doubleSided && cosFront < 0.0f);
            const float cosS = glm::dot(s.n, wi);
            if (emits && cosS > 0.0f && glm::dot(s.ng, wi) > 0.0f) {
                const glm::vec3 f = core::evalBrdf(s.brdf, s.n, wo, wi);
                if (!isZero(f)) {
                    // The solid-angle density of the light sample: p_A r^2 / |cos_light|.
                    const float pdfLight = ls.pdfArea * dist2 / std::abs(cosFront);
                    const glm::vec3 shadow = ls.p - origin;
                    const float shadowLen = glm::length(shadow);
                    const float tMax = shadowLen - 2.0f * EmbreeScene::offsetScale(ls.p);
                    if (tMax > 0.0f && !geometry_.occluded(origin, shadow / shadowLen, 0.0f, tMax, rays)) {
                        const float weight = powerHeuristic(pdfLight, core::pdfBrdf(s.brdf, s.n, wo, wi));
                        sum += f * ls.radiance * (cosS * weight / pdfLight);
                    }
                }
            }
        }
    }
    return sum;
}

glm::vec3 Integrator::directLight(const Shading& s, const glm::vec3& wo, core::Pcg32& rng, std::uint64_t& rays) const
{
    glm::vec3 sum = lightSample(s, wo, rng, rays);
    if (!lights_.hasAreaLights()) return sum; // BRDF sampling finds no emitter: punctual lights are delta
    const float u1 = rng.nextFloat();
    const glm::vec2 u23 = rng.next2();
    const core::BrdfSample bs = core::sampleBrdf(s.brdf, s.n, wo, u1, u23.x, u23.y);
    if (!bs.valid || isZero(bs.f) || glm::dot(s.ng, bs.wi) <= 0.0f) return sum;
    Hit hit;
    if (!geometry_.intersect(EmbreeScene::offsetOrigin(s.surface.p, s.ng), bs.wi, 0.0f, kInfinity, hit, rays))
        return sum;
    const SurfacePoint e = geometry_.surface(hit);
    const glm::vec3 le = LightTable::emitted(*e.material, e.ng, -bs.wi);
    if (isZero(le)) return sum;
    const float weight = brdfHitWeight(bs.pdf, s.surface.p, e);
    return sum + bs.f * le * (glm::dot(s.n, bs.wi) * weight / bs.pdf);
}

glm::vec3 Integrator::noVisibilityBounce(const Shading& s, const glm::vec3& wo, core::Pcg32& rng,
                                         std::uint64_t& rays) const
{
    // L2(x1 -> wo) = integral over all surface points x2 of f(x1) L_direct(x2 -> x1) cos1 cos2 / r^2 dA,
    // with no visibility between x1 and x2. Changing variables to directions at x1 (dA = r^2 / cos2 dw)
    // turns it into: integral over directions of f cos1 times the SUM of L_direct(x2 -> x1) over every
    // surface the ray from x1 crosses. So: one BRDF-sampled direction, every crossing of that line,
    // each crossing's reflected direct light (with full light visibility). The back of a one-sided
    // surface reflects nothing, as everywhere else.
    const float u1 = rng.nextFloat();
    const glm::vec2 u23 = rng.next2();
    const core::BrdfSample bs = core::sampleBrdf(s.brdf, s.n, wo, u1, u23.x, u23.y);
    if (!bs.valid || isZero(bs.f) || glm::dot(s.ng, bs.wi) <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 throughput = bs.f * (glm::dot(s.n, bs.wi) / bs.pdf);
    thread_local std::vector<Hit> hits;
    geometry_.allHits(EmbreeScene::offsetOrigin(s.surface.p, s.ng), bs.wi, 0.0f, kInfinity, hits, rays);
    glm::vec3 sum(0.0f);
    for (const Hit& hit : hits) {
        Shading x2;
        if (!shade(hit, -bs.wi, x2) || !x2.reflects) continue;
        sum += directLight(x2, -bs.wi, rng, rays);
    }
    return throughput * sum;
}

glm::vec3 Integrator::radiance(const glm::vec3& o, const glm::vec3& d, core::Pcg32& rng, std::uint64_t& rays) const
{
    glm::vec3 radiance(0.0f), beta(1.0f);
    Hit hit;
    if (!geometry_.intersect(o, d, 0.0f, kInfinity, hit, rays)) return radiance;
    glm::vec3 wo = -d, previous = o;
    float previousPdf = 0.0f;
    // k counts the reflections between the light and the camera of the paths completed at this vertex
    // by emission; next-event estimation and BRDF-sampled emission from here complete paths of k + 1.
    for (int k = 0;; ++k) {
        Shading s;
        const bool front = shade(hit, wo, s);
        if (inRange(k)) {
            const glm::vec3 le = LightTable::emitted(*s.surface.material, s.surface.ng, wo);
            // Seen by the camera directly, emission has no competing strategy; later, MIS with the light
            // sample of the previous vertex.
            if (!isZero(le)) radiance += beta * le * (k == 0 ? 1.0f : brdfHitWeight(previousPdf, previous, s.surface));
        }
        if (!front || !s.reflects) break;
        if (noVisibility_ && k == 0) radiance += beta * noVisibilityBounce(s, wo, rng, rays);
        if (k + 1 > maxReflections_) break;
        if (inRange(k + 1)) radiance += beta * lightSample(s, wo, rng, rays);

        const float u1 = rng.nextFloat();
        const glm::vec2 u23 = rng.next2();
        const core::BrdfSample bs = core::sampleBrdf(s.brdf, s.n, wo, u1, u23.x, u23.y);
        if (!bs.valid || isZero(bs.f) || glm::dot(s.ng, bs.wi) <= 0.0f) break;
        beta *= bs.f * (glm::dot(s.n, bs.wi) / bs.pdf);
        if (russianRoulette_ && k + 1 >= kRouletteStart) {
            const float keep = std::min(kRouletteMaxKeep, maxComponent(beta));
            if (rng.nextFloat() >= keep) break;
            beta /= keep;
        }
        previous = s.surface.p;
        previousPdf = bs.pdf;
        if (!geometry_.intersect(EmbreeScene::offsetOrigin(s.surface.p, s.ng), bs.wi, 0.0f, kInfinity, hit, rays))
            break;
        wo = -bs.wi;
    }
    return radiance;
}

} // namespace bounce::ref
