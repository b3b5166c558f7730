// Interpolation of the samples' irradiance to every shading point (section 3.4), as irradiance caching
// does (Ward et al. 1988): E(x) = sum_j w_j E_j / sum_j w_j over the samples near x, with
// w_j = 1 / (|x - s_j| / R_j + sqrt(2 - 2 n(x) . n(s_j))). "Near": the samples whose error 1 / w_j is
// below `maxError` (found through the tree of samples, pruned by distance over the largest R_j below a
// node), and always the sample of x's own cluster. Written as E_own + sum w_j (E_j - E_own) / sum w_j: the
// same quantity, but a field that is the same at every sample comes out exactly that value. A point on
// a sample (w infinite) takes that sample's irradiance. The outgoing radiance is the BRDF's reflection of
// E as if it came evenly from the hemisphere: the diffuse part c_diff / pi with the Fresnel transmission
// out (1 - w F(n.v)) and in (1 - w F_avg, F_avg = F0 + (1 - F0) / 21, Schlick's term averaged over the
// cosine-weighted hemisphere), plus the glossy part w (F0 A + B) / pi, A and B Karis' (2014) fit of the
// GGX lobe's directional albedo. The paper interpolates spherical harmonics for glossy last bounces
// (section 3.4); the albedo is exact only for uniform incident light, and good for rough lobes. With
// GLOSSY_SAMPLED the glossy part is left out: photon_glossy.comp adds it, sampled from the lobe.
//
// Shared by the pass's two forms (Interpolation::run chooses): photon_interpolate.frag, a full-screen
// triangle, and photon_interpolate.comp, one invocation per pixel, for GPUs whose graphics units are few
// (on an NVIDIA H200 the fragment form took 9.6 ms at 1024x768 whatever the scene).
#ifndef BOUNCE_PHOTON_INTERPOLATE_GLSL
#define BOUNCE_PHOTON_INTERPOLATE_GLSL

#include "common/gbuffer.glsl"
#include "technique/photon/cluster_point_tree.glsl"

layout(std430, binding = SSBO_CLUSTER_OF_PIXEL) readonly buffer ClusterOfPixel { uint clusterOfPixel[]; };

uniform ivec2 viewport;
uniform uint clusterCount;
uniform float maxError;
uniform int ownSampleOnly; // every pixel its own sample (gathering at every pixel)
uniform int writeIrradiance; // tests: write E itself instead of the radiance it reflects
uniform vec3 cameraPosition;

// sqrt(2 - 2 n . n_j) of Ward's weight, written as the chord |n - n_j|: the same for unit normals, but 0 for
// equal ones, where the square root of 2 - 2 (1 - 1 ulp) is 5e-4 and a point on its own sample missed it.
float normalGap(vec3 n, vec3 nj) { return length(n - nj); }

vec3 interpolate(vec3 x, vec3 n, uint own)
{
    Cluster c = clusters[own];
    vec3 base = c.irradiance.rgb;
    float ownError = length(x - c.samplePoint.xyz) / c.irradiance.w + normalGap(n, c.sampleNormal.xyz);
    if (ownSampleOnly != 0 || ownError <= 1e-6) return base;
    float weights = 1.0 / ownError;
    vec3 sum = vec3(0.0);
    uint i = 1u;
    while (i != 0u) {
        PointNode node = pointNodes[i];
        if (node.lo.w <= 0.0) {
            i = pointSkip(i);
        } else if (findMSB(i) == pointTreeDepth) {
            uint j = floatBitsToUint(node.hi.w);
            Cluster s = clusters[j];
            float e = length(x - s.samplePoint.xyz) / s.irradiance.w + normalGap(n, s.sampleNormal.xyz);
            if (j != own && e < maxError) {
                float w = 1.0 / max(e, 1e-6);
                weights += w;
                sum += w * (s.irradiance.rgb - base);
            }
            i = pointSkip(i);
        } else if (pointBoxDistance(x, node.lo.xyz, node.hi.xyz) >= maxError * node.hi.w) {
            i = pointSkip(i);
        } else {
            i = 2u * i;
        }
    }
    return base + sum / weights;
}

// What pixel q reflects towards the camera (or its irradiance, with writeIrradiance); 0 without a sample.
vec4 interpolatedRadiance(ivec2 q)
{
    GSurface g = gbufferSurface(q);
    if (!g.geometry) return vec4(0.0, 0.0, 0.0, 1.0);
    uint own = clusterOfPixel[q.y * viewport.x + q.x];
    if (own >= clusterCount || clusters[own].samplePoint.w < 0.0) return vec4(0.0, 0.0, 0.0, 1.0);
    vec3 x = g.position, n = g.normal;
    vec3 e = max(interpolate(x, n, own), vec3(0.0));
    if (writeIrradiance != 0) return vec4(e, 1.0);
    vec4 diffuse = gbufferDiffuse(q);
    vec4 specular = gbufferSpecular(q);
    vec3 f0 = specular.rgb;
    float cosView = max(dot(n, normalize(cameraPosition - x)), 0.0);
    vec3 out_ = 1.0 - diffuse.a * (f0 + (1.0 - f0) * pow(clamp(1.0 - cosView, 0.0, 1.0), 5.0));
    vec3 in_ = 1.0 - diffuse.a * (f0 + (1.0 - f0) / 21.0);
    // Karis 2014, "Physically Based Shading on Mobile": the split-sum DFG term as scale A and bias B of F0.
    vec4 r = specular.a * vec4(-1.0, -0.0275, -0.572, 0.022) + vec4(1.0, 0.0425, 1.04, -0.04);
    float a004 = min(r.x * r.x, exp2(-9.28 * cosView)) * r.x + r.y;
    vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
#ifdef GLOSSY_SAMPLED
    vec3 glossy = vec3(0.0);
#else
    vec3 glossy = diffuse.a * (f0 * ab.x + ab.y);
#endif
    return vec4((diffuse.rgb * out_ * in_ + glossy) / 3.14159265358979323846 * e, 1.0);
}

#endif
