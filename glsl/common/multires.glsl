// The multiresolution eye-space buffer of image-space radiosity (Nichols, Shopf & Wyman 2009, §3.2;
// gl/frame/multires.h builds the pyramid and upsamples; gl/technique/isr/multires_gather.h selects and gathers).
//
// Levels. Level 0 is the image (W x H pixels); a level-l patch covers 2^l x 2^l pixels, so level l has
// ceil(W / 2^l) x ceil(H / 2^l) patches and the parent of patch t is t >> 1 at every size (odd sizes and
// non-powers of two included: there is no padding, pixels beyond the image are simply absent). Pixels
// beyond the image and background pixels are "no geometry": they take no part in any min, max or mean.
//
// Flattened buffer (§3.2.1). All levels side by side in one 2D image: level 0 at x in [0, W), levels
// l >= 1 in one column to its right, level 1 at the bottom: levelOrigin[l], levelSize[l]. The min-max
// pyramid textures (mr*) hold levels 1..coarsestLevel in the same layout shifted left by W; level 0 is
// read from the G-buffer itself.
//
// Discontinuity (Fig. 2c). A patch of level l >= 1 with geometry needs subdividing when
//   (max d - min d) >= depthThreshold * min d     (d: linear eye depth, gbufferEyeDepth; relative threshold)
//   or max_c (max N_c - min N_c) >= normalThreshold  (componentwise spread of its unit normals)
// A single pixel never does. With ">=" a threshold of 0 subdivides everything: full resolution.
// Valid fragment (the pseudo code of §3.2.1): a patch with geometry, without discontinuity, whose parent
// has one (at the coarsest level: without discontinuity). Ranges only grow towards the parents, so
// every pixel with geometry lies in exactly one valid fragment.
#ifndef BOUNCE_MULTIRES_GLSL
#define BOUNCE_MULTIRES_GLSL

#include "common/gbuffer.glsl"

#define MULTIRES_MAX_LEVELS 16

uniform ivec2 levelOrigin[MULTIRES_MAX_LEVELS];
uniform ivec2 levelSize[MULTIRES_MAX_LEVELS];
uniform int coarsestLevel;
uniform float depthThreshold;
uniform float normalThreshold;

layout(binding = UNIT_MULTIRES_FIRST + 0) uniform sampler2D mrPosition;   // xyz mean world position (m), w pixels with geometry
layout(binding = UNIT_MULTIRES_FIRST + 1) uniform sampler2D mrNormal;     // xyz mean of the unit normals (not renormalised), w state
layout(binding = UNIT_MULTIRES_FIRST + 2) uniform sampler2D mrDiffuse;    // rgb mean diffuse colour
layout(binding = UNIT_MULTIRES_FIRST + 3) uniform sampler2D mrDepthRange; // (min d, max d) eye depth (m); (1e30, -1e30) when empty
layout(binding = UNIT_MULTIRES_FIRST + 4) uniform sampler2D mrNormalMin;  // xyz componentwise min of the unit normals; 2 when empty
layout(binding = UNIT_MULTIRES_FIRST + 5) uniform sampler2D mrNormalMax;  // xyz componentwise max; -2 when empty

struct MultiresPatch {
    vec3 position;     // mean world position of its pixels with geometry
    float count;       // how many pixels with geometry it has (0: none)
    vec3 normal;       // mean of their unit normals (length <= 1)
    vec3 diffuse;      // mean diffuse colour
    vec2 depthRange;   // min, max eye depth
    vec3 normalMin;
    vec3 normalMax;
};

MultiresPatch emptyPatch()
{
    MultiresPatch p;
    p.position = vec3(0.0);
    p.count = 0.0;
    p.normal = vec3(0.0);
    p.diffuse = vec3(0.0);
    p.depthRange = vec2(1e30, -1e30);
    p.normalMin = vec3(2.0);
    p.normalMax = vec3(-2.0);
    return p;
}

bool levelContains(int level, ivec2 t)
{
    return all(greaterThanEqual(t, ivec2(0))) && all(lessThan(t, levelSize[level]));
}

// Texel of patch t of level l >= 1 in the pyramid textures.
ivec2 pyramidTexel(int level, ivec2 t) { return levelOrigin[level] - ivec2(levelSize[0].x, 0) + t; }

// Pixel t of level 0 as a patch (empty outside the image or without geometry).
MultiresPatch loadPixel(ivec2 t)
{
    MultiresPatch p = emptyPatch();
    if (!levelContains(0, t)) return p;
    GSurface s = gbufferSurface(t);
    if (!s.geometry) return p;
    p.position = s.position;
    p.count = 1.0;
    p.normal = s.normal;
    p.diffuse = gbufferDiffuse(t).rgb;
    p.depthRange = vec2(s.eyeDepth);
    p.normalMin = s.normal;
    p.normalMax = s.normal;
    return p;
}

// Patch t of level >= 1 (empty outside the level).
MultiresPatch loadPyramidPatch(int level, ivec2 t)
{
    MultiresPatch p = emptyPatch();
    if (!levelContains(level, t)) return p;
    ivec2 a = pyramidTexel(level, t);
    vec4 pc = texelFetch(mrPosition, a, 0);
    p.position = pc.xyz;
    p.count = pc.w;
    p.normal = texelFetch(mrNormal, a, 0).xyz;
    p.diffuse = texelFetch(mrDiffuse, a, 0).rgb;
    p.depthRange = texelFetch(mrDepthRange, a, 0).xy;
    p.normalMin = texelFetch(mrNormalMin, a, 0).xyz;
    p.normalMax = texelFetch(mrNormalMax, a, 0).xyz;
    return p;
}

// Patch t of any level. A shader that knows its level at compile time should call one of the two above:
// a SIMD rasteriser runs both paths of this one whenever the level is not a constant.
MultiresPatch loadPatch(int level, ivec2 t)
{
    return level == 0 ? loadPixel(t) : loadPyramidPatch(level, t);
}

// Fig. 2c, IsDiscontinuity: the test on a patch's depth and normal ranges (min-max pass).
bool rangesDiscontinuous(vec2 depthRange, vec3 normalMin, vec3 normalMax)
{
    if (depthRange.y - depthRange.x >= depthThreshold * depthRange.x) return true;
    vec3 spread = normalMax - normalMin;
    return max(spread.x, max(spread.y, spread.z)) >= normalThreshold;
}

// Patch states, classified once by the min-max pass (multires_minmax.comp) and kept in mrNormal.w, so
// that the stencil pass reads one texel per level it looks at.
const float kPatchEmpty = 0.0;         // no pixel with geometry
const float kPatchContinuous = 1.0;
const float kPatchDiscontinuous = 2.0; // needs subdividing

float patchState(int level, ivec2 t)
{
    if (level > coarsestLevel || !levelContains(level, t)) return kPatchEmpty;
    if (level == 0) return gbufferHasGeometry(t) ? kPatchContinuous : kPatchEmpty; // a pixel never subdivides
    return texelFetch(mrNormal, pyramidTexel(level, t), 0).w;
}

// §3.2.1's pseudo code: valid where this level needs no subdivision (IsDiscontinuity(f, i) false) and
// the next coarser one does (NoDiscontinuity(f, i + 1) false); at the coarsest level, where it needs none.
bool fragmentValid(int level, ivec2 t)
{
    if (patchState(level, t) != kPatchContinuous) return false;
    return level == coarsestLevel || patchState(level + 1, t >> 1) == kPatchDiscontinuous;
}

struct PatchRanges {
    vec2 depthRange;
    vec3 normalMin, normalMax;
};

// The depth and normal ranges of patch t of level >= 1.
PatchRanges loadRanges(int level, ivec2 t)
{
    ivec2 a = pyramidTexel(level, t);
    return PatchRanges(texelFetch(mrDepthRange, a, 0).xy, texelFetch(mrNormalMin, a, 0).xyz,
                       texelFetch(mrNormalMax, a, 0).xyz);
}

// Whether two neighbouring patches of one level lie on one smooth surface, so that light may be
// interpolated between them: the gap between their eye-depth intervals is below the depth threshold
// (a continuous surface leaves at most one pixel's depth step between them, a depth edge more), and
// their joint normal spread is below 3 x the normal threshold (over two side-by-side patches of s
// pixels a linearly varying normal spans up to (2s - 1) / (s - 1) <= 3 times one patch's spread).
bool sameSurface(PatchRanges a, PatchRanges b)
{
    float gap = max(b.depthRange.x - a.depthRange.y, a.depthRange.x - b.depthRange.y);
    if (gap >= depthThreshold * min(a.depthRange.x, b.depthRange.x)) return false;
    vec3 spread = max(a.normalMax, b.normalMax) - min(a.normalMin, b.normalMin);
    return max(spread.x, max(spread.y, spread.z)) < 3.0 * normalThreshold;
}

// Bit of the neighbour at offset d (|d.x|, |d.y| <= 1) in the mask of same-surface neighbours.
uint neighbourBit(ivec2 d) { return 1u << uint((d.y + 1) * 3 + d.x + 1); }

// Which of the 8 neighbours of valid fragment t at level >= 1 are valid fragments of the same level on
// the same smooth surface: those the upsampling may interpolate with.
uint sameSurfaceNeighbours(int level, ivec2 t)
{
    uint mask = 0u;
    if (level == 0) return mask; // pixels are never interpolated
    PatchRanges own = loadRanges(level, t);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 c = t + ivec2(dx, dy);
            if (c == t || !fragmentValid(level, c)) continue;
            if (sameSurface(own, loadRanges(level, c))) mask |= neighbourBit(ivec2(dx, dy));
        }
    return mask;
}

// Which level and patch texel `a` of the flattened buffer belongs to; false outside every level.
bool locateInFlattened(ivec2 a, out int level, out ivec2 t)
{
    for (int l = 0; l <= coarsestLevel; ++l) {
        ivec2 local = a - levelOrigin[l];
        if (levelContains(l, local)) {
            level = l;
            t = local;
            return true;
        }
    }
    level = -1;
    t = ivec2(0);
    return false;
}

#endif
