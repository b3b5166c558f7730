// Reading the k-buffer of one global ray-bundle (Sec. 4.2), whichever capture wrote it, and finding the
// sender of a receiver among a pixel's entries (Fig. 5). An entry is (atlas texel + 1, depth); 0 is empty.
//   KBUFFER_STENCIL: a multisample array, KBUFFER_SAMPLES samples per layer (slice), entry i in sample
//     i % S of slice i / S; a pixel overflowed when the routing stencil of the last sample reached 0.
//   KBUFFER_ATOMIC: a 2D array, entry i in layer i; the per-pixel counter holds the fragment count.
//   KBUFFER_PEEL: a 2D array, layer i the i-th depth layer; a pixel overflowed when one more layer exists.
// KBUFFER_K: entries per pixel.
#ifndef BOUNCE_GRB_KBUFFER_GLSL
#define BOUNCE_GRB_KBUFFER_GLSL

#include "technique/grb/atlas.glsl"
#include "technique/grb/bindings.glsl"
#include "technique/grb/bundle.glsl"

#if defined(KBUFFER_STENCIL)
layout(binding = UNIT_GRB_KBUFFER) uniform sampler2DMSArray kbufferEntries;
layout(binding = UNIT_GRB_KBUFFER_STENCIL) uniform usampler2DMS kbufferStencil;
#else
layout(binding = UNIT_GRB_KBUFFER) uniform sampler2DArray kbufferEntries;
#endif
#if defined(KBUFFER_ATOMIC) || defined(KBUFFER_PEEL)
layout(binding = UNIT_GRB_KBUFFER_COUNT) uniform usampler2D kbufferCount;
#endif

vec2 kbufferEntry(ivec2 px, int i)
{
#if defined(KBUFFER_STENCIL)
    return texelFetch(kbufferEntries, ivec3(px, i / KBUFFER_SAMPLES), i % KBUFFER_SAMPLES).rg;
#else
    return texelFetch(kbufferEntries, ivec3(px, i), 0).rg;
#endif
}

// How many entries to read, and whether the pixel held more fragments than the k-buffer keeps.
int kbufferCountAt(ivec2 px, out bool overflow)
{
#if defined(KBUFFER_ATOMIC)
    uint count = texelFetch(kbufferCount, px, 0).r;
    overflow = count > uint(KBUFFER_K);
    return int(min(count, uint(KBUFFER_K)));
#elif defined(KBUFFER_PEEL)
    overflow = texelFetch(kbufferCount, px, 0).r != 0u; // the overflow layer
    return KBUFFER_K;
#else
    // The routing stencil of the last sample started at 1 + K and lost one per fragment (kbuffer.cpp).
    overflow = texelFetch(kbufferStencil, px, KBUFFER_SAMPLES - 1).r == 0u;
    return KBUFFER_K;
#endif
}

uint entryTexel(vec2 e) { return floatBitsToUint(e.x); } // atlas texel + 1, 0: empty

// One receiver's sample of a direction: whether it counts (the receiver found itself in a pixel that did
// not overflow), its sender's atlas texel + 1 (0: the ray leaves the scene or hits a back face first),
// the direction towards the sender and the receiver's cosine.
struct BundleSample {
    bool counts;
    uint sender;
    vec3 wi;
    float cosine;
};

// Receivers at grazing angles to the bundle take part with nothing: their cosine weight is below this
// (the cosine-weighted share of the hemisphere left out is its square, 4e-4).
const float kGrazingCosine = 0.02;

// The sender of receiver p (face normal nf, shading normal ns, atlas chart + 1, 0: any): p projects into
// its pixel, finds itself among the entries by depth (Sec. 4.2: the entry nearest the depth of p's plane
// at the pixel's centre, within a tolerance that grows as the plane turns edge-on, and of p's own chart,
// so that a coplanar surface beyond a wall is never taken for p), and takes the nearest entry on the
// side its face normal faces (the paper sorts the entries; the nearest one on a side is the same
// neighbour). ATLAS_TEXTURES must be defined (the charts).
#ifdef ATLAS_TEXTURES
BundleSample bundleSender(vec3 p, vec3 nf, vec3 ns, uint chart)
{
    BundleSample s;
    s.counts = false;
    s.sender = 0u;
    float sn = dot(nf, bundleDir);
    bool front = sn < 0.0; // p faces the near side: its light arrives along +bundleDir from smaller depths
    s.wi = front ? -bundleDir : bundleDir;
    s.cosine = max(dot(ns, s.wi), 0.0);
    if (abs(sn) < kGrazingCosine) {
        s.counts = true;
        s.cosine = 0.0;
        return s;
    }
    ivec2 px = ivec2(floor(bundlePixel(p)));
    if (any(lessThan(px, ivec2(0))) || any(greaterThanEqual(px, ivec2(kbufferSize)))) return s;
    bool overflow;
    int n = kbufferCountAt(px, overflow);
    if (overflow) return s; // entries are missing: the nearest one on a side may not be the neighbour

    // The depth of p's plane at the pixel's centre.
    vec2 off = bundleOffsetToPixelCentre(p, px);
    float depth = bundleDepth(p) - (off.x * dot(bundleRight, nf) + off.y * dot(bundleUp, nf)) / sn;
    float pixel = 2.0 * bundleRadius / float(kbufferSize);
    float tangent = min(sqrt(max(1.0 - sn * sn, 0.0)) / abs(sn), 50.0);
    float tolerance = 2e-5 * bundleRadius + 0.75 * pixel * tangent;

    // Among the entries within the tolerance, the nearest of p's chart (a coplanar surface back to back
    // with p, the other side of a wall of no thickness, lies at the same depth).
    float selfDist = 1e30, selfDepth = 0.0;
    for (int i = 0; i < n; ++i) {
        vec2 e = kbufferEntry(px, i);
        uint t = entryTexel(e);
        float d = abs(e.y - depth);
        if (t == 0u || d > tolerance || d >= selfDist) continue;
        if (chart != 0u && atlasChart(atlasTexelOf(t - 1u)) != chart) continue;
        selfDist = d;
        selfDepth = e.y;
    }
    if (selfDist > tolerance) return s; // p's surface is not in its pixel (an edge, a corner): no sample
    s.counts = true;
    // Entries at p's own depth up to rounding are p's surface or one back to back with it: not neighbours.
    float coincident = 1e-6 * bundleRadius / abs(sn);
    float best = front ? -1e30 : 1e30;
    for (int i = 0; i < n; ++i) {
        vec2 e = kbufferEntry(px, i);
        uint t = entryTexel(e);
        if (t == 0u || abs(e.y - selfDepth) <= coincident) continue;
        bool candidate = front ? (e.y < selfDepth && e.y > best) : (e.y > selfDepth && e.y < best);
        if (candidate) {
            best = e.y;
            s.sender = t;
        }
    }
    return s;
}
#endif

#endif
