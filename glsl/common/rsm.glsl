// The reflective shadow map of image-space radiosity (Nichols, Shopf & Wyman 2009, §3.2.2-3.4) as every
// ISR pass reads it (gl/frame/rsm.h writes it). One layer per light view (a spot: one
// perspective view; a point light or an area light: six cube faces; a directional light: one
// orthographic view). Each layer is a pyramid atlas: level 0 (the RSM proper, size x size texels) at
// x in [0, size), and, when the pass was asked for levels, level l >= 1 ((size >> l)^2 patches of
// 2^l x 2^l texels) to its right at x = size, y = size - (size >> (l - 1)). Read with texelFetch only.
//
//                      level 0 (the RSM)                 levels >= 1 (patches of 2^l x 2^l texels)
//   rsmPosition        xyz world (m), w 1 / 0 (empty)    xyz area-weighted centroid of the lit texels (of
//                                                        all texels when none is lit), w number of
//                                                        non-empty texels
//   rsmNormal          xyz unit normal N_j,              xyz unit mean normal (lit texels weighted by
//                      w A_t = omega_t |V_t|^2 (Eq. 3)   their area), w sum of A_t over lit texels
//                      if lit, else 0
//   rsmFlux            rgb rho_j Phi_j (W), w omega_t    rgb sum of rho Phi, w sum of omega_t (sr) over
//                      (sr) if lit, else 0               the lit texels
//   rsmDepthRange      (d, d): light-space depth (m)     (min d, max d) over the non-empty texels
//   rsmNormalMin/Max   (N, 0)                            componentwise min / max of the unit normals
// "Lit" means the texel reflects flux: front side towards the light, inside the light's cone, albedo > 0.
// Light-space depth d is the distance |V| to the light for perspective views (so the max over a patch
// bounds |V_j| from above, as §3.5 needs) and the distance along the light direction for orthographic
// ones. Empty texels hold the neutral elements (d range (1e30, 0), normal min 2, max -2), so a patch
// with no geometry has min > max.
#ifndef BOUNCE_RSM_GLSL
#define BOUNCE_RSM_GLSL

#include "common/bindings.glsl"
layout(binding = UNIT_RSM_FIRST + 0) uniform sampler2DArray rsmPosition;
layout(binding = UNIT_RSM_FIRST + 1) uniform sampler2DArray rsmNormal;
layout(binding = UNIT_RSM_FIRST + 2) uniform sampler2DArray rsmFlux;
layout(binding = UNIT_RSM_FIRST + 3) uniform sampler2DArray rsmDepthRange;
layout(binding = UNIT_RSM_FIRST + 4) uniform sampler2DArray rsmNormalMin;
layout(binding = UNIT_RSM_FIRST + 5) uniform sampler2DArray rsmNormalMax;

// One light view of the RSM (std430 mirror of RsmPass's GpuRsmView), SSBO binding 10.
struct RsmView {
    mat4 viewProj;
    vec4 originOrtho;    // xyz light origin (orthographic: the view's eye point), w: 1 orthographic, 0 perspective
    vec4 directionTexel; // xyz view axis (the direction light travels for orthographic views), w: the side of
                         // a texel at the map's centre: at distance 1 (perspective) or in metres (orthographic)
};
layout(std430, binding = SSBO_RSM_VIEWS) readonly buffer RsmViews { RsmView rsmViews[]; };

// Atlas texel of patch p (patch coordinates at `level`) in a layer whose level 0 is size x size.
ivec2 rsmAtlasTexel(ivec2 p, int level, int size)
{
    if (level == 0) return p;
    return ivec2(size + p.x, size - (size >> (level - 1)) + p.y);
}

vec4 rsmFetch(sampler2DArray t, ivec2 p, int level, int view, int size)
{
    return texelFetch(t, ivec3(rsmAtlasTexel(p, level, size), view), 0);
}

// The light-space discontinuity test of §3.4 on one patch: a patch needs subdividing when it is not
// entirely covered by geometry, when its relative light-space depth range (max d - min d) / min d
// exceeds depthThreshold, or when any component of its unit normals spans more than normalThreshold.
bool rsmPatchContinuous(ivec2 p, int level, int view, int size, float depthThreshold, float normalThreshold)
{
    float count = rsmFetch(rsmPosition, p, level, view, size).w;
    if (count < float(1 << (2 * level)) - 0.5) return false;
    vec2 d = rsmFetch(rsmDepthRange, p, level, view, size).xy;
    if (d.y - d.x > depthThreshold * d.x) return false;
    vec3 spread = rsmFetch(rsmNormalMax, p, level, view, size).xyz - rsmFetch(rsmNormalMin, p, level, view, size).xyz;
    return max(spread.x, max(spread.y, spread.z)) <= normalThreshold;
}

#endif
