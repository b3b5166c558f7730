// The importance warp of one micro-buffer (Ritschel et al. 2009, §2.3), the GLSL twin of core/brdf_warp.h
// (its header explains the tabulation): the per-lobe tables (SSBO, built on the CPU) are mixed for this
// gather sample's BRDF and turned into marginal and conditional CDFs in shared memory by the work group
// ("each thread first computes the BRDF warping functions"); then
//   warpToDirection(u)   Phi: unit square -> local direction (z the normal), for ray casting and convolution
//   warpToUnit(w)        Phi^-1: local direction -> unit square, to rasterise a node
//   warpCosineSolidAngle(w)  cos theta Omega(Phi^-1(w)), the f-free part of a micro-pixel's weight
//   warpPixelSolidAngle(w)   Omega, what a node's solid angle is compared with (§2.2)
// WARP_BINS (K) and MICRO_RES (R) are #defines; the group has MICRO_GROUP invocations.
#ifndef BOUNCE_MICRO_WARP_GLSL
#define BOUNCE_MICRO_WARP_GLSL

#include "common/brdf.glsl"
#include "technique/microrender/bindings.glsl"

layout(std430, binding = SSBO_MICRO_WARP_TABLES) readonly buffer MicroWarpTables { float warpTables[]; };
uniform int warpCosSteps;           // the GGX tables' grid: cos theta_o steps
uniform int warpAlphaCount;         //   and alpha values
uniform float warpAlphas[16];

shared float warpMass[WARP_BINS * WARP_BINS];       // the mixture, then normalised
shared float warpRows[WARP_BINS * (WARP_BINS + 1)]; // conditional CDFs, one row per wx bin
shared float warpRowMass[WARP_BINS];
shared float warpMarginal[WARP_BINS + 1];

// core::BrdfWarpTables::ggxTable: the nearest grid point in cos theta_o and log alpha.
int warpGgxTable(float cosThetaO, float alpha)
{
    int ic = clamp(int(clamp(cosThetaO, 0.0, 1.0) * float(warpCosSteps)), 0, warpCosSteps - 1);
    int ia = 0;
    float la = log(max(alpha, 1e-6));
    for (int k = 1; k < warpAlphaCount; ++k)
        if (abs(log(warpAlphas[k]) - la) < abs(log(warpAlphas[ia]) - la)) ia = k;
    return 1 + ia * warpCosSteps + ic;
}

// core::warpSpecularShare: the glossy lobe's share of the micro-buffer.
float warpSpecularShare(BrdfParams b, float cosThetaO)
{
    if (b.weight <= 0.0) return 0.0;
    vec3 f = b.f0 + (1.0 - b.f0) * pow(1.0 - clamp(cosThetaO, 0.0, 1.0), 5.0);
    const vec3 lum = vec3(0.2126, 0.7152, 0.0722);
    float wF = b.weight * dot(f, lum);
    float d = dot(b.diffuse, lum) * max(0.0, 1.0 - wF);
    if (d <= 0.0) return 1.0;
    return wF / (wF + d);
}

// Builds the CDFs of (1 - share) table 0 + share table ggx. Every invocation of the group must call it.
void warpBuild(float share, int ggx, uint lid)
{
    const int k2 = WARP_BINS * WARP_BINS;
    for (int k = int(lid); k < k2; k += MICRO_GROUP)
        warpMass[k] = (1.0 - share) * warpTables[k] + (share > 0.0 ? share * warpTables[ggx * k2 + k] : 0.0);
    barrier();
    for (int i = int(lid); i < WARP_BINS; i += MICRO_GROUP) {
        float run = 0.0;
        for (int j = 0; j < WARP_BINS; ++j) run += warpMass[i * WARP_BINS + j];
        float acc = 0.0;
        for (int j = 0; j <= WARP_BINS; ++j) {
            warpRows[i * (WARP_BINS + 1) + j] = run > 0.0 ? acc / run : float(j) / float(WARP_BINS);
            if (j < WARP_BINS) acc += warpMass[i * WARP_BINS + j];
        }
        warpRows[i * (WARP_BINS + 1) + WARP_BINS] = 1.0;
        warpRowMass[i] = run;
    }
    barrier();
    if (lid == 0u) {
        float total = 0.0;
        for (int i = 0; i < WARP_BINS; ++i) total += warpRowMass[i];
        float acc = 0.0;
        for (int i = 0; i <= WARP_BINS; ++i) {
            warpMarginal[i] = total > 0.0 ? acc / total : float(i) / float(WARP_BINS);
            if (i < WARP_BINS) acc += warpRowMass[i];
        }
        warpMarginal[WARP_BINS] = 1.0;
        warpRowMass[0] = total; // reused: the total, for the densities below (rows are done with it)
    }
    barrier();
    float total = warpRowMass[0];
    barrier();
    for (int k = int(lid); k < k2; k += MICRO_GROUP) warpMass[k] = total > 0.0 ? warpMass[k] / total : 1.0 / float(k2);
    barrier();
}

// The bin k with cdf[k] <= u < cdf[k + 1] of the marginal (row < 0) or of a row's conditional.
int warpSearch(int row, float u, out float frac)
{
    int base = row < 0 ? 0 : row * (WARP_BINS + 1);
    int lo = 0, hi = WARP_BINS;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        float c = row < 0 ? warpMarginal[mid] : warpRows[base + mid];
        if (c <= u)
            lo = mid;
        else
            hi = mid;
    }
    float c0 = row < 0 ? warpMarginal[lo] : warpRows[base + lo];
    float c1 = row < 0 ? warpMarginal[lo + 1] : warpRows[base + lo + 1];
    float width = c1 - c0;
    frac = width > 0.0 ? clamp((u - c0) / width, 0.0, 1.0) : 0.5;
    return lo;
}

vec3 warpToDirection(vec2 u)
{
    float fx, fy;
    int i = warpSearch(-1, u.x, fx);
    int j = warpSearch(i, u.y, fy);
    float angle = 0.5 * kPi * (-1.0 + 2.0 * (float(i) + fx) / float(WARP_BINS));
    float v = -1.0 + 2.0 * (float(j) + fy) / float(WARP_BINS);
    float wx = sin(angle), s = cos(angle);
    float wy = v * s;
    return vec3(wx, wy, sqrt(max(0.0, 1.0 - wx * wx - wy * wy)));
}

// The bin of w (marginal over a = atan2(wx, s) / (pi / 2), conditional over v = wy / s) and s^2, with
// s = |(wy, wz)| = cos(pi a / 2) (asin(wx) would lose its precision near the rim).
ivec2 warpBin(vec3 w, out vec2 frac, out float s2)
{
    float wz = max(w.z, 0.0);
    s2 = w.y * w.y + wz * wz;
    float s = sqrt(s2);
    float v = s > 0.0 ? clamp(w.y / s, -1.0, 1.0) : 0.0;
    vec2 t = (vec2(atan(w.x, s) / (0.5 * kPi), v) + 1.0) * 0.5 * float(WARP_BINS);
    ivec2 b = clamp(ivec2(floor(t)), ivec2(0), ivec2(WARP_BINS - 1));
    frac = clamp(t - vec2(b), 0.0, 1.0);
    return b;
}

vec2 warpToUnit(vec3 w)
{
    vec2 f;
    float s2;
    ivec2 b = warpBin(w, f, s2);
    float x = warpMarginal[b.x] + f.x * (warpMarginal[b.x + 1] - warpMarginal[b.x]);
    int r = b.x * (WARP_BINS + 1);
    float y = warpRows[r + b.y] + f.y * (warpRows[r + b.y + 1] - warpRows[r + b.y]);
    return vec2(x, y);
}

// (pi / 2) s^2 / (R^2 q), q = mass K^2 / 4: cos theta x Omega of the micro-pixel at w (0 where no mass).
float warpCosineSolidAngle(vec3 w)
{
    vec2 f;
    float s2;
    ivec2 b = warpBin(w, f, s2);
    float q = warpMass[b.x * WARP_BINS + b.y] * float(WARP_BINS * WARP_BINS) * 0.25;
    return q > 0.0 ? 0.5 * kPi * s2 / (float(MICRO_RES * MICRO_RES) * q) : 0.0;
}

// Omega of the micro-pixel at w: 1 / (R^2 pdf); infinite at the horizon and where the warp has no mass.
float warpPixelSolidAngle(vec3 w)
{
    float cs = warpCosineSolidAngle(w);
    return (cs > 0.0 && w.z > 0.0) ? cs / w.z : 1e30;
}

// core::BrdfWarp::cellSample / cellOf: micro-pixel c covers [c / R, (c + 1) / R)^2, its direction taken
// at (c + 0.5 + j) / R with the sample's jitter j in (-0.5, 0.5)^2.
vec2 warpCellSample(ivec2 c, vec2 jitter) { return (vec2(c) + 0.5 + jitter) / float(MICRO_RES); }

ivec2 warpCellOf(vec2 u) { return clamp(ivec2(floor(u * float(MICRO_RES))), ivec2(0), ivec2(MICRO_RES - 1)); }

#endif
