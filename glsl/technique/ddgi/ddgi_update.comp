#version 450 core
// The atlases' update (Majercik et al. 2019, section 5.1, Eqs. 2 and 3): one work group per probe and one
// invocation per inner texel of its tile. An inner texel blends this frame's rotated rays of
// its probe: the irradiance map their radiance weighted by max(0, cos) to the texel's direction,
// normalised by the weights' sum (the cosine-weighted mean radiance, pi times which is the irradiance E);
// with DEPTH, the moments map their distance d and d^2 (clamped to maxDistance) weighted by
// max(0, cos)^50. The result is blended with what the texel held: mix(new, old, hysteresis). Then the
// group writes every texel of the tile, border included, from shared memory with the inner texel it holds
// (probes.glsl, octBorderSource), so that the border equals that texel exactly, without a second pass.
// Inactive probes (classification) keep what they held.
//
// The moments' lobe, cos^50, is narrow (half its weight within 0.17 rad): the rays are first sorted into
// the map's inner texels (in shared memory, by counting), and a texel sums only the rays of the 5 x 5
// texels around it, folded across the map's edges (octFoldTexel), instead of every ray: about 8 times
// fewer terms at 256 rays per probe. What it leaves out lies at least two texels away (0.36 rad or more),
// where the weight is under 1.5% of its peak. The irradiance's lobe is the whole hemisphere: every ray.
//
// FAST_TRANSITIONS: a texel whose new estimate lies far from what it held takes less of the old, so that a
// light switched on, a probe just made and a change of scene settle in a few frames instead of the 1 / (1 -
// hysteresis) frames (times the bounces) of the plain blend: the 2021 paper's heuristics to speed
// transitions (section 3), with thresholds chosen here: a relative change (of the luminance, or of the mean
// distance) over 0.25 lowers the hysteresis by 0.15, one over 0.8 sets it to 0.
#include "common/brdf.glsl"
#include "technique/ddgi/probes.glsl"
#include "technique/ddgi/rays.glsl"

#ifdef DEPTH
const int kInner = kDepthInner;
layout(local_size_x = 14, local_size_y = 14) in;
layout(rg32f, binding = 0) uniform image2D atlas;
const int kChunk = 1024; // rays sorted at a time
const int kBins = kInner * kInner;
const int kReach = 2;    // texels around a texel whose rays it sums
shared vec4 chunkRays[kChunk]; // xyz direction, w distance
shared uint rayBin[kChunk];
shared uint sortedRays[kChunk];
shared uint binCount[kBins], binStart[kBins + 1], binCursor[kBins];
#else
const int kInner = kIrradianceInner;
layout(local_size_x = 6, local_size_y = 6) in;
layout(rgba32f, binding = 0) uniform image2D atlas;
const int kChunk = 64;
shared vec4 chunkRays[kChunk];  // rgb radiance
shared vec3 chunkDirections[kChunk];
#endif
const int kGroup = kInner * kInner;
shared vec4 blended[kInner * kInner];

layout(std430, binding = SSBO_DDGI_RAYS) readonly buffer DdgiRays { vec4 rays[]; };

uniform int raysPerProbe;
uniform int fixedRays;
uniform mat3 rayRotation;
uniform float hysteresis;  // the share of what the texel held that it keeps
uniform float maxDistance; // the moments' distances are clamped to it

// The hysteresis for a texel whose estimate went from `old` to `current` (FAST_TRANSITIONS).
float transitionHysteresis(float current, float old)
{
#ifdef FAST_TRANSITIONS
    float change = abs(current - old) / max(max(abs(current), abs(old)), 1e-30);
    if (change > 0.8) return 0.0;
    if (change > 0.25) return max(hysteresis - 0.15, 0.0);
#endif
    return hysteresis;
}

// max(0, c)^50 in seven multiplications (pow is exp2 of log2 in a software renderer).
float depthWeight(float c)
{
    float c2 = max(c, 0.0) * max(c, 0.0), c4 = c2 * c2, c8 = c4 * c4, c16 = c8 * c8, c32 = c16 * c16;
    return c32 * c16 * c2;
}

void main()
{
    int probe = int(gl_WorkGroupID.x);
    if (!probeActive(probe)) return; // the whole group: one probe
    ivec2 source = ivec2(gl_LocalInvocationID.xy); // the inner texel this invocation blends
    int local = source.y * kInner + source.x;
    vec3 texelDirection = octTexelDirection(source, kInner);
    int first = probe * (fixedRays + raysPerProbe) + fixedRays; // the probe's first rotated ray
    vec4 sum = vec4(0.0);
    float weights = 0.0;
    for (int start = 0; start < raysPerProbe; start += kChunk) {
        int count = min(kChunk, raysPerProbe - start);
#ifdef DEPTH
        for (int i = local; i < kBins; i += kGroup) binCount[i] = binCursor[i] = 0u;
        barrier();
        for (int j = local; j < count; j += kGroup) {
            vec3 d = probeRayDirection(fixedRays + start + j, fixedRays, raysPerProbe, rayRotation);
            chunkRays[j] = vec4(d, rays[first + start + j].a);
            ivec2 t = clamp(ivec2((octEncode(d) * 0.5 + 0.5) * float(kInner)), ivec2(0), ivec2(kInner - 1));
            rayBin[j] = uint(t.y * kInner + t.x);
            atomicAdd(binCount[rayBin[j]], 1u);
        }
        barrier();
        if (local == 0) {
            uint offset = 0u;
            for (int i = 0; i < kBins; ++i) {
                binStart[i] = offset;
                offset += binCount[i];
            }
            binStart[kBins] = offset;
        }
        barrier();
        for (int j = local; j < count; j += kGroup)
            sortedRays[binStart[rayBin[j]] + atomicAdd(binCursor[rayBin[j]], 1u)] = uint(j);
        barrier();
        for (int dy = -kReach; dy <= kReach; ++dy)
            for (int dx = -kReach; dx <= kReach; ++dx) {
                ivec2 t = octFoldTexel(source + ivec2(dx, dy), kInner);
                int bin = t.y * kInner + t.x;
                for (uint k = binStart[bin]; k < binStart[bin + 1]; ++k) {
                    vec4 ray = chunkRays[sortedRays[k]];
                    float w = depthWeight(dot(texelDirection, ray.xyz)), d = min(abs(ray.w), maxDistance);
                    sum.xy += w * vec2(d, d * d);
                    weights += w;
                }
            }
#else
        for (int j = local; j < count; j += kGroup) {
            chunkRays[j] = rays[first + start + j];
            chunkDirections[j] = probeRayDirection(fixedRays + start + j, fixedRays, raysPerProbe, rayRotation);
        }
        barrier();
        for (int j = 0; j < count; ++j) {
            float w = max(dot(texelDirection, chunkDirections[j]), 0.0);
            sum.rgb += w * chunkRays[j].rgb;
            weights += w;
        }
#endif
        barrier();
    }
    ivec2 tile = probeTile(probe, kInner + 2);
    vec4 old = imageLoad(atlas, tile + 1 + source);
    if (weights <= 0.0) {
        blended[local] = old; // no ray near this texel's direction this frame: it keeps what it held
    } else {
#ifdef DEPTH
        vec4 current = vec4(sum.xy / weights, 0.0, 0.0);
        float h = transitionHysteresis(current.x, old.x);
#else
        vec4 current = vec4(kPi * sum.rgb / weights, 1.0);
        float h = transitionHysteresis(dot(current.rgb, kLuminance), dot(old.rgb, kLuminance));
#endif
        blended[local] = mix(current, old, h);
    }
    barrier();
    const int side = kInner + 2;
    for (int i = local; i < side * side; i += kGroup) {
        ivec2 b = ivec2(i % side, i / side), held = octBorderSource(b, kInner);
        imageStore(atlas, tile + b, blended[held.y * kInner + held.x]);
    }
}
