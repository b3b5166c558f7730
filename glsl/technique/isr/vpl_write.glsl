// Writing side of the VPL cache (technique/isr/vpl.glsl): the cache at binding 8 as a writable block,
// the optional append counter at binding 9, and the VPL a patch of RSM texels becomes.
#ifndef BOUNCE_ISR_VPL_WRITE_GLSL
#define BOUNCE_ISR_VPL_WRITE_GLSL

#include "technique/isr/vpl.glsl"
#include "technique/isr/bindings.glsl"
#include "common/rsm.glsl"

layout(std430, binding = SSBO_ISR_VPL_CACHE) writeonly buffer VplCacheOut { Vpl outVpls[]; };

// A VPL that contributes nothing anywhere (zero flux, zero normal, unit area: no 0/0 in Eq. 1).
Vpl inertVpl()
{
    Vpl v;
    v.positionArea = vec4(0.0, 0.0, 0.0, 1.0);
    v.normal = vec4(0.0);
    v.flux = vec4(0.0);
    return v;
}

// The VPL of a patch of RSM texels at `position` with normal n: reflected flux rho_j Phi_j, solid angle
// omega_j, level. Area by Eq. 3, A_j = omega_j |V_j|^2 (orthographic views: the patch's summed texel
// area orthoArea instead), at least 1e-12 m^2 so that Eq. 1 stays finite on the VPL itself.
Vpl makeVpl(int view, vec3 position, vec3 n, vec3 reflectedFlux, float omega, float orthoArea, float level)
{
    RsmView rv = rsmViews[view];
    float area;
    if (rv.originOrtho.w != 0.0) {
        area = orthoArea;
    } else {
        vec3 v = position - rv.originOrtho.xyz;
        area = omega * dot(v, v);
    }
    Vpl o;
    o.positionArea = vec4(position, max(area, 1e-12));
    o.normal = vec4(n, level);
    o.flux = vec4(reflectedFlux, omega);
    return o;
}

// The VPL that stands for the texels [lo, hi) of a view when they are not one continuous patch: its
// flux is the block's whole reflected flux (so the total matches the RSM), its position and normal are
// those of the lit texel nearest the block centre (a point sample, as the regular grid of the paper).
// Inert when no texel of the block is lit.
Vpl blockVpl(int view, ivec2 lo, ivec2 hi, float level)
{
    vec3 sum = vec3(0.0);
    float omega = 0.0, area = 0.0, best = 1e30;
    ivec2 pick = ivec2(-1);
    vec2 centre = 0.5 * vec2(lo + hi);
    for (int y = lo.y; y < hi.y; ++y)
        for (int x = lo.x; x < hi.x; ++x) {
            vec4 f = texelFetch(rsmFlux, ivec3(x, y, view), 0);
            if (max(f.r, max(f.g, f.b)) <= 0.0) continue;
            sum += f.rgb;
            omega += f.w;
            area += texelFetch(rsmNormal, ivec3(x, y, view), 0).w;
            vec2 d = vec2(x, y) + 0.5 - centre;
            float d2 = dot(d, d);
            if (d2 < best) { best = d2; pick = ivec2(x, y); }
        }
    if (pick.x < 0) return inertVpl();
    vec3 p = texelFetch(rsmPosition, ivec3(pick, view), 0).xyz;
    vec3 n = texelFetch(rsmNormal, ivec3(pick, view), 0).xyz;
    return makeVpl(view, p, n, sum, omega, area, level);
}

#endif
