// The probe field of DDGI (Majercik, Guertin, Nowrouzezahrai & McGuire 2019, "Dynamic Diffuse Global
// Illumination with Ray-Traced Irradiance Fields", JCGT 8(2)), and what every pass of the family shares:
// - the grid: probe (x, y, z) sits at gridOrigin + (x, y, z) gridSpacing plus its own offset (probe
//   relocation, Majercik, Marrs, Spjut & McGuire 2021, section 4), index x + nx (y + ny z);
// - the atlases (section 4.1, Fig. 5): one square tile per probe, at column index % atlasColumns and row
//   index / atlasColumns; a tile holds the octahedral map (common/packing.glsl, octEncode) of the sphere
//   around the probe in its n x n inner texels and a one-texel border that holds the inner texels across
//   the map's folded edges, so that a bilinear lookup wraps across the tile's edge (n = 6 for irradiance,
//   14 for the distance moments);
// - ddgiIrradiance: the irradiance at a surface from the eight probes around it (section 5.2, Listing 2).
#ifndef BOUNCE_DDGI_PROBES_GLSL
#define BOUNCE_DDGI_PROBES_GLSL

#include "common/packing.glsl"
#include "technique/ddgi/bindings.glsl"

const int kIrradianceInner = 6; // texels per side of a probe's irradiance map, without the border
const int kDepthInner = 14;     // and of its distance moments

uniform vec3 gridOrigin;  // probe (0, 0, 0)'s grid point
uniform vec3 gridSpacing; // between grid points along each axis
uniform ivec3 gridCounts; // probes along each axis, at least 2
uniform int atlasColumns; // probe tiles per row of the atlases

layout(std430, binding = SSBO_DDGI_PROBES) buffer DdgiProbes { vec4 probeStates[]; };

int probeIndex(ivec3 q) { return q.x + gridCounts.x * (q.y + gridCounts.y * q.z); }
ivec3 probeCell(int i) { return ivec3(i % gridCounts.x, (i / gridCounts.x) % gridCounts.y, i / (gridCounts.x * gridCounts.y)); }
vec3 probeGridPoint(int i) { return gridOrigin + vec3(probeCell(i)) * gridSpacing; }
vec3 probePosition(int i) { return probeGridPoint(i) + probeStates[i].xyz; }
bool probeActive(int i) { return probeStates[i].w != 0.0; }

// The tile's first texel (its border's corner) for tiles of `side` texels, inner plus border.
ivec2 probeTile(int i, int side) { return ivec2(i % atlasColumns, i / atlasColumns) * side; }

// The unit direction at the centre of inner texel t (0 .. inner-1 per axis) of an octahedral map.
vec3 octTexelDirection(ivec2 t, int inner) { return octDecode((vec2(t) + 0.5) * (2.0 / float(inner)) - 1.0); }

// Texel t of an octahedral map of n x n texels, carried past the map's edges by whole texels, folded back
// onto the map: the edges fold onto themselves ((1, v) and (1, -v) are one direction), so texel (n + k, v)
// is texel (n - 1 - k, n - 1 - v), and past a corner the map folds twice, onto the diagonally opposite
// corner. Valid up to n texels out.
ivec2 octFoldTexel(ivec2 t, int n)
{
    if (t.x < 0) t = ivec2(-1 - t.x, n - 1 - t.y);
    else if (t.x >= n) t = ivec2(2 * n - 1 - t.x, n - 1 - t.y);
    if (t.y < 0) t = ivec2(n - 1 - t.x, -1 - t.y);
    else if (t.y >= n) t = ivec2(n - 1 - t.x, 2 * n - 1 - t.y);
    return t;
}

// The inner texel a tile's texel b (0 .. inner+1 per axis, the border included) holds: an inner texel
// itself, a border texel the inner texel across the edge, so that a bilinear lookup wraps as the map does.
ivec2 octBorderSource(ivec2 b, int inner) { return octFoldTexel(b - 1, inner); }

// Where a bilinear lookup of direction d reads probe i's tile, in texels of the atlas.
vec2 octAtlasTexel(int i, vec3 d, int inner)
{
    return vec2(probeTile(i, inner + 2)) + 1.0 + (octEncode(d) * 0.5 + 0.5) * float(inner);
}

#ifdef DDGI_SHADING
layout(binding = UNIT_DDGI_IRRADIANCE) uniform sampler2D irradianceAtlas; // rgb: irradiance E
layout(binding = UNIT_DDGI_DEPTH) uniform sampler2D depthAtlas;           // rg: mean distance and its square

uniform float selfShadowBias; // the paper's bias, per the smallest grid spacing (Sec. 5.2: 0.3)

float cube(float x) { return x * x * x; }

// Irradiance at point p with normal n, seen along wo, from the eight probes of its grid cell: each weighted
// by the trilinear weight, the smooth backface term ((1 + cos) / 2)^2 + 0.2, Chebyshev's bound on the
// probe's visibility of the biased point from its distance moments (cubed, at least 0.05), and the
// weights under 0.2 crushed (w^3 / 0.04), as section 5.2 and Listing 2 shape them. Inactive probes
// (classification) weigh nothing. The paper blends the square roots of the irradiances and squares the
// sum, for the eye; this blends the irradiances themselves, whose weighted mean keeps the probes' energy.
vec3 ddgiIrradiance(vec3 p, vec3 n, vec3 wo)
{
    float minSpacing = min(gridSpacing.x, min(gridSpacing.y, gridSpacing.z));
    vec3 biased = p + (0.2 * n + 0.8 * wo) * (0.75 * minSpacing * selfShadowBias);
    vec3 g = (biased - gridOrigin) / gridSpacing;
    ivec3 base = clamp(ivec3(floor(g)), ivec3(0), gridCounts - 2);
    vec3 alpha = clamp(g - vec3(base), 0.0, 1.0);
    vec2 irradianceScale = 1.0 / vec2(textureSize(irradianceAtlas, 0));
    vec2 depthScale = 1.0 / vec2(textureSize(depthAtlas, 0));
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int c = 0; c < 8; ++c) {
        ivec3 corner = ivec3(c & 1, (c >> 1) & 1, c >> 2);
        int i = probeIndex(base + corner);
        vec4 state = probeStates[i];
        vec3 q = probeGridPoint(i) + state.xyz;
        vec3 toProbe = q - p;
        float towards = dot(normalize(toProbe), n);
        float w = 0.25 * (towards + 1.0) * (towards + 1.0) + 0.2;
        vec3 fromProbe = biased - q;
        float r = max(length(fromProbe), 1e-20);
        vec2 moments = textureLod(depthAtlas, octAtlasTexel(i, fromProbe / r, kDepthInner) * depthScale, 0.0).rg;
        if (r > moments.x) {
            float variance = abs(moments.x * moments.x - moments.y), over = r - moments.x;
            w *= max(cube(variance / (variance + over * over)), 0.05);
        }
        w = max(w, 1e-6);
        const float crush = 0.2;
        if (w < crush) w *= w * w / (crush * crush);
        vec3 tri = mix(1.0 - alpha, alpha, vec3(corner));
        w *= tri.x * tri.y * tri.z * state.w;
        sum += w * textureLod(irradianceAtlas, octAtlasTexel(i, n, kIrradianceInner) * irradianceScale, 0.0).rgb;
        weights += w;
    }
    return weights > 0.0 ? sum / weights : vec3(0.0);
}
#endif

#endif
