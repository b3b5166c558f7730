#version 450 core
// Temporal reuse of one signal (gl/frame/temporal_reuse.h): this pixel's surface point, rebuilt from the
// G-buffer, projected through the previous frame's camera; the previous output there (four texels,
// bilinear weights, each kept only on this point's surface by the previous G-buffer) is clamped to the
// current signal's 3x3 neighbourhood (CLAMP_HISTORY) and blended with the current value by an exponential
// moving average whose weight is 1/n over the first n frames of a history (Schied et al. 2017,
// "Spatiotemporal Variance-Guided Filtering", sec. 4.1; its variance and a-trous filter are not here).
// CATMULL_ROM: the history resampled by Catmull-Rom's cubic where its 16 texels are all kept.
#include "common/bindings.glsl"
#include "common/gbuffer.glsl"

layout(binding = UNIT_TEMPORAL_CURRENT) uniform sampler2D current;
layout(binding = UNIT_TEMPORAL_HISTORY) uniform sampler2D history;
layout(binding = UNIT_TEMPORAL_HISTORY_LENGTH) uniform sampler2D historyLength;
// The previous frame's gGeometry: eye depth bits (0: no geometry) and the octahedral normal.
layout(binding = UNIT_TEMPORAL_PREVIOUS_GEOMETRY) uniform usampler2D previousGeometry;

uniform mat4 previousViewProjection; // world to the previous frame's clip space, without its jitter
uniform vec2 currentJitter;          // this frame's sample offset from the pixel centre (pixels)
uniform int hasHistory;              // 0: the first frame after a reset or a resize
uniform float alpha;                 // the new sample's weight once the history is 1/alpha frames long
uniform float depthTolerance;        // relative eye depth
uniform float normalTolerance;       // 1 - cos

layout(location = 0) out vec4 outSignal; // the blend, the next frame's history, copied back over the signal
layout(location = 1) out float outLength; // frames the blend averages (0: no geometry)

// A reprojected position this close to a texel centre (in pixels, per axis) takes that texel alone: the
// position rebuilt from depth is off by float rounding (~1e-4 pixel at 256 pixels), and a still camera or a
// whole-pixel move would otherwise blur the history by that fraction of its neighbours every frame.
const float kSnapPixels = 1.0 / 64.0;
// A neighbour's surface counts for this pixel's history only where it moves on screen with this pixel's own
// point (previous pixel coordinates less current ones, within this per axis): a surface whose edge straddles
// the pixel moves with it, while the surface that a nearer edge uncovers by parallax (a wall beside a box
// the camera passes) moves otherwise, and taking the box's history there left a trail behind the edge as
// long as the parallax per frame over alpha (cornell-spot along bench/paths/cornell-orbit.json: the direct
// light's reuse read 29% with no such test, 19% with it; gl/frame/README.md). A trail is at most this over
// alpha pixels long.
const float kMotionPixels = 0.15;
// Valid taps holding less of the bilinear weight than this are no history (disocclusion), as in SVGF.
const float kMinHistoryWeight = 0.01;

bool isFinite(vec4 v) { return !any(isnan(v)) && !any(isinf(v)); }

// Whether texel p lies inside the viewport (a negative coordinate wraps to a large unsigned one: one test
// per axis instead of two).
bool inside(ivec2 p, ivec2 size) { return all(lessThan(uvec2(p), uvec2(size))); }


// The current signal's range over the 3x3 pixels around px (inside the viewport).
void neighbourhood(ivec2 px, ivec2 size, out vec3 lo, out vec3 hi)
{
    lo = vec3(1e30);
    hi = vec3(-1e30);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            vec3 c = texelFetch(current, clamp(px + ivec2(dx, dy), ivec2(0), size - 1), 0).rgb;
            lo = min(lo, c);
            hi = max(hi, c);
        }
}

// What a previous texel must match to be this pixel's history: a surface of this pixel or of one of its
// 3x3 neighbours, each as the previous camera sees it (eye depth) with its normal: the texel's normal within
// the tolerance of theirs, its eye depth within the span of their depths (widened by the tolerance). The neighbours count
// because still frames jitter (FrameSampler::jitter): where a pixel's footprint straddles two surfaces
// (a silhouette, a corner), one frame's sample lands on one and the next frame's on the other, and both
// belong to the pixel's box-filtered value; testing against its own sample alone restarted the history at
// every such pixel each time the sample changed surface, and those pixels never averaged. A neighbour's
// surface counts only where it moves on screen with this pixel's own point (kMotionPixels). A surface that
// no pixel around sees any more (a disocclusion) still takes no history.
struct Neighbour {
    float depth; // eye depth in the previous camera (0: no geometry)
    vec3 normal;
    vec2 motion; // its previous pixel coordinates less its current ones (pixels)
};

// Where the point of the current G-buffer at pixel px, projected by the previous camera (clip), lay in the
// previous frame's pixel coordinates (texel centres at integers). The point lies at px's centre plus this
// frame's jitter, which is taken off: the history is kept at pixel centres.
vec2 previousPixel(vec4 clip, ivec2 size) { return (clip.xy / clip.w * 0.5 + 0.5) * vec2(size) - 0.5 - currentJitter; }

Neighbour neighbourAt(ivec2 px, ivec2 size)
{
    Neighbour n = Neighbour(0.0, vec3(0.0), vec2(0.0));
    if (!inside(px, size)) return n;
    uvec2 g = texelFetch(gGeometry, px, 0).xy;
    if (g.x == 0u) return n;
    vec4 clip = previousViewProjection * vec4(gbufferPositionAt(px, uintBitsToFloat(g.x)), 1.0);
    if (clip.w <= 0.0) return n;
    n.depth = clip.w;
    n.normal = unpackUnitVector(g.y);
    n.motion = previousPixel(clip, size) - vec2(px);
    return n;
}

// Whether the previous frame's texel t is this pixel's history (the test above, against the neighbours
// around), and its value and length there (zero where it is not).
bool historyTap(ivec2 t, vec2 q, ivec2 px, Neighbour around[9], ivec2 size, out vec4 h, out float n)
{
    h = vec4(0.0);
    n = 0.0;
    if (!inside(t, size)) return false; // off screen
    uvec2 g = texelFetch(previousGeometry, t, 0).xy;
    if (g.x == 0u) return false; // the previous frame saw background there
    float tapDepth = uintBitsToFloat(g.x);
    vec3 tapNormal = unpackUnitVector(g.y);
    // The depths of the neighbours with the tap's normal span what a sample anywhere in this pixel sees
    // of their surfaces (at a grazing angle one pixel spans more depth than the tolerance).
    float lo = 1e30, hi = 0.0;
    for (int k = 0; k < 9; ++k)
        if (around[k].depth > 0.0 && dot(tapNormal, around[k].normal) >= 1.0 - normalTolerance &&
            all(lessThanEqual(abs(around[k].motion - (q - vec2(px))), vec2(kMotionPixels)))) {
            lo = min(lo, around[k].depth);
            hi = max(hi, around[k].depth);
        }
    if (tapDepth < lo * (1.0 - depthTolerance) || tapDepth > hi * (1.0 + depthTolerance)) return false;
    h = texelFetch(history, t, 0);
    n = texelFetch(historyLength, t, 0).r;
    bool kept = isFinite(h) && n >= 1.0; // a NaN or infinity in the history is dropped, not spread
    h = kept ? h : vec4(0.0);
    n = kept ? n : 0.0;
    return kept;
}

// Whether the previous frame's texel t saw this pixel's own surface (eye depth `depth` in the previous
// camera, normal `normal`) and holds a finite history there, and that history (zero where not): the test of
// the texels around the four, cheaper than theirs (one surface, not the nine around), and stricter.
bool ownSurfaceTap(ivec2 t, float depth, vec3 normal, ivec2 size, out vec3 h)
{
    h = vec3(0.0);
    if (!inside(t, size)) return false;
    uvec2 g = texelFetch(previousGeometry, t, 0).xy;
    if (g.x == 0u || abs(uintBitsToFloat(g.x) - depth) > depthTolerance * depth ||
        dot(unpackUnitVector(g.y), normal) < 1.0 - normalTolerance)
        return false;
    // A texel with geometry holds a history of at least one frame: its length is not read.
    vec4 v = texelFetch(history, t, 0);
    h = isFinite(v) ? v.rgb : vec3(0.0);
    return isFinite(v);
}

// One of the twelve texels around the four: kept where it saw this pixel's own surface, or where it carries
// no weight (`needed` false: Catmull-Rom gives the outer texels of an axis weight 0 where the fraction along
// it is 0).
bool outerTap(ivec2 t, bool needed, float depth, vec3 normal, ivec2 size, out vec3 h)
{
    return ownSurfaceTap(t, depth, normal, size, h) || !needed;
}

// The weighted sum of one row (or column) of four texels.
vec3 weighted(vec4 w, vec3 a, vec3 b, vec3 c, vec3 d) { return w.x * a + w.y * b + w.z * c + w.w * d; }

// Catmull-Rom's weights of the four texels at -1, 0, 1, 2 from the texel below a point at fraction t.
vec4 catmullRomWeights(float t)
{
    float t2 = t * t, t3 = t2 * t;
    return vec4(-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0, -1.5 * t3 + 2.0 * t2 + 0.5 * t, 0.5 * t3 - 0.5 * t2);
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(current, 0);
    vec4 now = texelFetch(current, px, 0);
    outSignal = now;
    GSurface s = gbufferSurface(px);
    outLength = s.geometry ? 1.0 : 0.0;
    if (!s.geometry || hasHistory == 0) return; // background passes the current value; no history yet

    vec4 clip = previousViewProjection * vec4(s.position, 1.0);
    if (clip.w <= 0.0) return; // behind the previous camera
    vec2 q = previousPixel(clip, size);
    q = mix(q, round(q), lessThan(abs(q - round(q)), vec2(kSnapPixels)));
    ivec2 base = ivec2(floor(q));
    vec2 f = q - vec2(base);

    Neighbour around[9];
    for (int i = 0; i < 9; ++i) around[i] = neighbourAt(px + ivec2(i % 3 - 1, i / 3 - 1), size);

    // The four texels around q, written out tap by tap as the twelve below are: llvmpipe kept the loop over
    // the sixteen as a loop, with its indexing into arrays, and the pass took 1.3 times as long.
    vec4 bilinear = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    vec4 h00, h10, h01, h11, tapLength;
    bvec4 valid = bvec4(historyTap(base, q, px, around, size, h00, tapLength.x),
                        historyTap(base + ivec2(1, 0), q, px, around, size, h10, tapLength.y),
                        historyTap(base + ivec2(0, 1), q, px, around, size, h01, tapLength.z),
                        historyTap(base + ivec2(1, 1), q, px, around, size, h11, tapLength.w));
    vec4 w = mix(vec4(0.0), bilinear, valid);
    float weightSum = w.x + w.y + w.z + w.w;
    if (weightSum < kMinHistoryWeight) return; // disoccluded: the history restarts here

    vec3 previous = weighted(w, h00.rgb, h10.rgb, h01.rgb, h11.rgb) / weightSum;
    float historyFrames = dot(w, tapLength) / weightSum;
    // The range of the texels that carry weight.
    vec3 tapLo = vec3(1e30), tapHi = vec3(-1e30);
    vec3 taps[4] = vec3[4](h00.rgb, h10.rgb, h01.rgb, h11.rgb);
    for (int i = 0; i < 4; ++i) {
        tapLo = w[i] > 0.0 ? min(tapLo, taps[i]) : tapLo;
        tapHi = w[i] > 0.0 ? max(tapHi, taps[i]) : tapHi;
    }
#ifdef CATMULL_ROM
    // Where the four texels are all kept and the twelve around them (those of nonzero weight) saw this
    // pixel's own surface, Catmull-Rom's cubic in place of the bilinear blend: a camera that moves by
    // fractions of a pixel resamples the history every frame, and the bilinear tent blurs it each time (the
    // detail of a texture or a shadow's edge fades over the frames the history averages); the cubic keeps it.
    // Clamped to the four texels' range, against the cubic's overshoot. A linear signal comes back as the
    // bilinear blend gives it.
    if (weightSum >= 1.0 - 1e-6) {
        vec4 wx = catmullRomWeights(f.x), wy = catmullRomWeights(f.y);
        bool nx = f.x > 0.0, ny = f.y > 0.0;
        vec3 below[4], above[4], left[2], right[2]; // rows -1 and 2, columns -1 and 2 of rows 0 and 1
        bvec4 rowBelow = bvec4(outerTap(base + ivec2(-1, -1), nx && ny, clip.w, s.normal, size, below[0]),
                               outerTap(base + ivec2(0, -1), ny, clip.w, s.normal, size, below[1]),
                               outerTap(base + ivec2(1, -1), ny, clip.w, s.normal, size, below[2]),
                               outerTap(base + ivec2(2, -1), nx && ny, clip.w, s.normal, size, below[3]));
        bvec4 rowAbove = bvec4(outerTap(base + ivec2(-1, 2), nx && ny, clip.w, s.normal, size, above[0]),
                               outerTap(base + ivec2(0, 2), ny, clip.w, s.normal, size, above[1]),
                               outerTap(base + ivec2(1, 2), ny, clip.w, s.normal, size, above[2]),
                               outerTap(base + ivec2(2, 2), nx && ny, clip.w, s.normal, size, above[3]));
        bvec4 sides = bvec4(outerTap(base + ivec2(-1, 0), nx, clip.w, s.normal, size, left[0]),
                            outerTap(base + ivec2(-1, 1), nx, clip.w, s.normal, size, left[1]),
                            outerTap(base + ivec2(2, 0), nx, clip.w, s.normal, size, right[0]),
                            outerTap(base + ivec2(2, 1), nx, clip.w, s.normal, size, right[1]));
        vec3 cubic = wy.x * weighted(wx, below[0], below[1], below[2], below[3]) +
                     wy.y * weighted(wx, left[0], h00.rgb, h10.rgb, right[0]) +
                     wy.z * weighted(wx, left[1], h01.rgb, h11.rgb, right[1]) +
                     wy.w * weighted(wx, above[0], above[1], above[2], above[3]);
        if (all(rowBelow) && all(rowAbove) && all(sides)) previous = clamp(cubic, tapLo, tapHi);
    }
#endif
#ifdef CLAMP_HISTORY
    vec3 lo, hi;
    neighbourhood(px, size, lo, hi);
    previous = clamp(previous, lo, hi);
#endif
    float n = min(historyFrames + 1.0, 1.0 / alpha);
    float weight = max(alpha, 1.0 / n);
    // previous + (now - previous) w rather than mix(): equal inputs give that value exactly.
    outSignal = vec4(previous + (now.rgb - previous) * weight, now.a);
    outLength = n;
}
