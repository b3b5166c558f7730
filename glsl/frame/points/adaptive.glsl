// Image-space adaptive sampling (Maletz, Wang & Bowers 2011, §3.3): gather at the pixels of a 4 x 4 grid,
// then at the pixels of the 2 x 2 and 1 x 1 grids whose coherence metric
//   max_i ( |p_i - p_c| / (d / 2) + sqrt(2 - 2 n_i . n_c) ) + lambda sum_{j,k} |L_o(p_j) - L_o(p_k)|
// over their (up to) four parents on the coarser grid exceeds epsilon (doubled per level), and interpolate
// the others from those parents by joint bilateral weights. State per pixel (r8ui): kUndecided, kSampled,
// kInterpolated, kNoGeometry. The light is kept as two images: the diffuse part without the diffuse colour
// and the glossy part (§4: "we interpolate the diffuse and glossy incoming radiance separately, and multiply
// them with the textured reflectance values").
#ifndef BOUNCE_ADAPTIVE_GLSL
#define BOUNCE_ADAPTIVE_GLSL

#include "common/gbuffer.glsl"

const uint kUndecided = 0u;
const uint kSampled = 1u;
const uint kInterpolated = 2u;
const uint kNoGeometry = 3u;

uniform ivec2 viewSize;
uniform int spacing;        // the coarser grid's spacing S: candidates lie on the S / 2 grid, off the S grid
uniform float sceneDiagonal; // d, metres

bool hasGeometry(ivec2 px) { return gbufferHasGeometry(px); }

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// L_o's luminance at px from its two light images (the diffuse part times the pixel's diffuse colour, plus
// the glossy part).
float luminanceOf(ivec2 px, vec3 diffuseLight, vec3 glossyLight)
{
    return luminance(gbufferDiffuse(px).rgb * diffuseLight + glossyLight);
}

// The display scale of L_o in the coherence metric (adaptive_mean.comp, adaptive_select.comp): L_o's
// luminance times kKey over the log-average luminance of the frame's light, which maps that log-average to
// middle grey (Reinhard et al. 2002's key 0.18), clamped at 1 as the paper's 8-bit L_o is. kLogDelta keeps
// a black pixel's logarithm finite.
const float kKey = 0.18;
const float kLogDelta = 1e-4;

bool onGrid(ivec2 px, int s) { return px.x % s == 0 && px.y % s == 0; }

// The parents of a candidate on the S grid: the corners of the grid cell around it (the image's last grid
// line closes the cell when there is no next one), as lo / hi corners; lo == hi on an axis the candidate
// lies on.
void parentBox(ivec2 px, int s, out ivec2 lo, out ivec2 hi)
{
    lo = (px / s) * s;
    hi = lo + ivec2(s);
    if (hi.x > viewSize.x - 1 || lo.x == px.x) hi.x = lo.x;
    if (hi.y > viewSize.y - 1 || lo.y == px.y) hi.y = lo.y;
}

// The geometric term of the metric between a parent and the candidate.
float geometricTerm(ivec2 parent, vec3 pc, vec3 nc)
{
    GSurface s = gbufferSurface(parent);
    vec3 pi = s.position;
    vec3 ni = s.normal;
    return length(pi - pc) / (0.5 * sceneDiagonal) + sqrt(max(0.0, 2.0 - 2.0 * dot(ni, nc)));
}

#endif
