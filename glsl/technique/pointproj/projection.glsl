// The closed forms of importance-driven point projection (Maletz, Wang & Bowers 2011), the GLSL twins of
// core/point_projection.h (tested there): the hemi-octahedral map (Eq. 2, with our z the normal), the
// robust solid angle (Eq. 5) and the per-point importance (Eq. 1; Eq. 4 multiplies f_r).
#ifndef BOUNCE_POINTPROJ_PROJECTION_GLSL
#define BOUNCE_POINTPROJ_PROJECTION_GLSL

// Eq. 2: w' = w / |w|_1, t = ((1 - w'.x + w'.y) / 2, (1 - w'.x - w'.y) / 2).
vec2 hemiOctEncode(vec3 w)
{
    float l1 = abs(w.x) + abs(w.y) + abs(w.z);
    vec3 p = l1 > 0.0 ? w / l1 : vec3(0.0, 0.0, 1.0);
    return vec2(0.5 * (1.0 - p.x + p.y), 0.5 * (1.0 - p.x - p.y));
}

vec3 hemiOctDecode(vec2 t)
{
    float x = 1.0 - t.x - t.y, y = t.x - t.y;
    return normalize(vec3(x, y, max(0.0, 1.0 - abs(x) - abs(y))));
}

// Eq. 5: 2 pi A cos / (A + 2 pi d^2), never above 2 pi cos theta_s.
float robustSolidAngle(float areaM2, float cosThetaS, float distance2)
{
    const float twoPi = 6.28318530717958647692;
    float den = areaM2 + twoPi * distance2;
    return den > 0.0 ? twoPi * areaM2 * abs(cosThetaS) / den : twoPi * abs(cosThetaS);
}

// Eq. 1: max(cos theta_p, 0) |cos theta_s| / d^2 dA.
float pointImportance(float cosThetaP, float cosThetaS, float distance2, float areaM2)
{
    return distance2 > 0.0 ? max(cosThetaP, 0.0) * abs(cosThetaS) / distance2 * areaM2 : 0.0;
}

#endif
