// Where a point-based final gather runs and where its result goes (shared by micro-rendering and point
// projection). Two kinds of target, chosen by a #define:
//   default           a valid fragment of the frame's multiresolution buffer (common/multires.glsl), listed
//                     by gather_select.comp: a pixel (level 0) or the mean position and normal of a
//                     coarser patch (the paper's gathering "at a subset of all image locations"); the BRDF
//                     from the G-buffer at the patch's middle pixel. The result goes to two flattened
//                     illumination images: rgb the diffuse part without the receiver's diffuse colour
//                     (alpha 1 + the same-surface neighbour mask, what frame/multires_upsample.glsl wants),
//                     and the glossy part, reflected radiance as it is (upsampled unmodulated).
//   GATHER_AT_POINTS  every stride-th point of the cloud, diffuse only (the multi-bounce iteration): the
//                     result, the diffuse part, goes to pointGathered for point_relight.comp.
#ifndef BOUNCE_GATHER_TARGET_GLSL
#define BOUNCE_GATHER_TARGET_GLSL

// Included before any #if: the shader preprocessor takes each file once, also inside an inactive branch.
#include "common/bindings.glsl"
#include "common/brdf.glsl"
#include "common/dispatch_rows.glsl"
#ifdef GATHER_AT_POINTS
#define POINT_SURFELS
#endif
#include "frame/points/point_cloud.glsl"

struct GatherSample {
    vec3 position;     // on the surface, metres
    vec3 normal;       // unit
    vec3 wo;           // unit, towards the viewer (the normal at points: they reflect diffusely)
    BrdfParams brdf;
    ivec2 texel;       // where the result goes (pixel targets), (k, 0) at points: what random numbers are keyed by
                       // (never the list index k of a pixel target, which follows the select pass's thread timing)
    float alpha;       // 1 + the neighbour mask (pixel targets)
};

#ifdef GATHER_AT_POINTS
layout(std430, binding = SSBO_POINT_GATHERED) writeonly buffer PointGathered { vec4 pointGathered[]; };
uniform uint gatherStride;
uniform uint targetCount;

uint gatherTargetCount() { return targetCount; }

GatherSample loadGatherSample(uint k)
{
    PointSurfel s = pointSurfels[k * gatherStride];
    GatherSample g;
    g.position = s.position;
    g.normal = s.normal;
    g.wo = s.normal;
    g.brdf.diffuse = unpackUnorm4x8(s.diffuse).rgb;
    g.brdf.f0 = vec3(0.0);
    g.brdf.weight = 0.0;
    g.brdf.alpha = 1.0;
    g.texel = ivec2(int(k), 0); // identifies the target (random numbers are keyed by it)
    g.alpha = 0.0;
    return g;
}

void storeGather(GatherSample g, uint k, vec3 diffuse, vec3 glossy) { pointGathered[k] = vec4(diffuse, 0.0); }

#else
#include "common/multires.glsl"

layout(std430, binding = SSBO_GATHER_TARGETS) readonly buffer GatherTargets { uint gatherCount; uint gatherPad; uvec2 gatherTargets[]; };
layout(rgba32f, binding = 0) uniform writeonly image2D illuminationDiffuse;
layout(rgba32f, binding = 1) uniform writeonly image2D illuminationGlossy;
uniform vec3 cameraPosition;

uint gatherTargetCount() { return gatherCount; }

// Target k: x | y << 16 of its flattened texel, and its neighbour mask | level << 16.
GatherSample loadGatherSample(uint k)
{
    uvec2 e = gatherTargets[k];
    GatherSample g;
    g.texel = ivec2(int(e.x & 0xFFFFu), int(e.x >> 16));
    int level = int(e.y >> 16);
    g.alpha = 1.0 + float(e.y & 0xFFFFu);
    ivec2 t = g.texel - levelOrigin[level];
    if (level == 0) {
        GSurface s = gbufferSurface(t);
        g.position = s.position;
        g.normal = s.normal;
        g.brdf = gbufferBrdf(t);
    } else {
        MultiresPatch p = loadPatch(level, t);
        g.position = p.position;
        g.normal = length(p.normal) > 0.0 ? normalize(p.normal) : vec3(0.0, 0.0, 1.0);
        ivec2 middle = min(t * (1 << level) + (1 << (level - 1)), levelSize[0] - 1);
        if (gbufferHasGeometry(middle)) {
            g.brdf = gbufferBrdf(middle);
        } else {
            g.brdf.diffuse = p.diffuse;
            g.brdf.weight = 0.0;
            g.brdf.f0 = vec3(0.0);
            g.brdf.alpha = 1.0;
        }
    }
    g.wo = normalize(cameraPosition - g.position);
    return g;
}

void storeGather(GatherSample g, uint k, vec3 diffuse, vec3 glossy)
{
    imageStore(illuminationDiffuse, g.texel, vec4(diffuse, g.alpha));
    imageStore(illuminationGlossy, g.texel, vec4(glossy, 1.0));
}
#endif

// The gather's target of this work group (one group per target, in rows: dispatchPerTarget).
uint gatherTargetIndex() { return rowGroup(); }

// The word a target's random numbers start from (common/random.glsl's hashU): its texel, or (k, 0) at
// points, through the primes of a spatial hash (Teschner et al. 2003), so that a target draws the same
// numbers in every run. Both gathers.
uint gatherTargetKey(GatherSample g) { return uint(g.texel.x) * 73856093u ^ uint(g.texel.y) * 19349663u; }

// The convolution step of both gathers: radiance arriving at the sample along wi (unit, world) through one
// micro-pixel or texel of the gather's buffer, weighted by its cosine times solid angle, through the
// sample's BRDF, added to the diffuse and glossy sums.
void gatherAdd(GatherSample g, vec3 wi, vec3 radiance, float weight, inout vec3 sumDiffuse, inout vec3 sumGlossy)
{
    vec3 fd, fg;
    brdfEvalLobes(g.brdf, g.normal, g.wo, wi, fd, fg);
    sumDiffuse += radiance * fd * weight;
    sumGlossy += radiance * fg * weight;
}

#endif
