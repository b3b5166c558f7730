#version 450 core
// Moving frames' edge antialiasing, the resolve (gl/frame/edge_antialias.h): a pixel sampled at its centre
// shows one surface even where an edge of the geometry crosses it; the box-filtered pixel the still frames
// converge to mixes the surfaces by the areas they cover. With the line of the nearest edge that bounds a
// surface (edges.geom: its unit normal out of its triangle n, and the signed distance s of the pixel's centre
// from it, positive on the triangle's side) that area is exact for one straight edge: the part of the pixel
// on the other side of the line from its centre, of area beyond(|s|), takes the light of the neighbour
// across the line on that side, where that neighbour shows another surface. A pixel whose centre lies on the
// triangle's side (s > 0) gives the part beyond the edge to what lies beyond it (the background of a
// silhouette, the other face of a crease); one whose centre lies outside (s < 0) takes from the triangle's
// side the part the triangle covers. Geometric post-process antialiasing (Persson, 2011), with the covered
// area in closed form instead of a linear ramp.
#include "common/gbuffer.glsl"

layout(binding = UNIT_EDGE_IMAGE) uniform sampler2D image;
layout(binding = UNIT_EDGE_LINES) uniform sampler2D lines;

layout(location = 0) out vec4 outRadiance;

// The area of the unit pixel, centred at 0, where dot(n, x) > s, for s >= 0 and a unit normal n: the
// pixel's extent along n is a trapezoid of half-width (a + b) / 2 with ramps of width b at its ends
// (a, b: the larger and smaller of |n.x|, |n.y|).
float areaBeyond(float s, vec2 n)
{
    float a = max(abs(n.x), abs(n.y)), b = min(abs(n.x), abs(n.y));
    float outer = 0.5 * (a + b), inner = 0.5 * (a - b);
    if (s >= outer) return 0.0;
    if (s > inner) {
        float r = outer - s;
        return r * r / (2.0 * a * b);
    }
    return 0.5 - s / a;
}

bool inImage(ivec2 q) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, textureSize(image, 0))); }

// Whether q shows another surface than p: one of them background, or normals or planes apart. Neighbours
// on one smooth surface (a triangle edge inside a mesh) are not mixed: that would only blur.
bool otherSurface(ivec2 p, ivec2 q)
{
    bool gp = gbufferHasGeometry(p), gq = gbufferHasGeometry(q);
    if (gp != gq) return true;
    if (!gp) return false;
    vec3 np = gbufferNormal(p);
    if (dot(np, gbufferNormal(q)) < 0.995) return true;
    return abs(dot(np, gbufferPosition(q) - gbufferPosition(p))) > 2e-3 * gbufferEyeDepth(p);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 own = texelFetch(image, p, 0).rgb;
    vec4 edge = texelFetch(lines, p, 0);
    float share = edge.w > 0.0 ? areaBeyond(abs(edge.z), edge.xy) : 0.0;
    if (!(share > 0.0)) {
        outRadiance = vec4(own, 1.0);
        return;
    }
    // The side of the line the centre is not on, and the neighbour there along the line's nearer axis. A
    // centre on the line (within 1/32 pixel) belongs to whichever side the rasteriser's tie rule gave it:
    // the other side is the one whose neighbour shows another surface.
    vec2 away = edge.z >= 0.0 ? edge.xy : -edge.xy;
    ivec2 step = abs(away.x) >= abs(away.y) ? ivec2(away.x > 0.0 ? 1 : -1, 0) : ivec2(0, away.y > 0.0 ? 1 : -1);
    bool across = inImage(p + step) && otherSurface(p, p + step);
    if (!across && abs(edge.z) < 1.0 / 32.0) {
        step = -step;
        across = inImage(p + step) && otherSurface(p, p + step);
    }
    if (across) own = mix(own, texelFetch(image, p + step, 0).rgb, share);
    outRadiance = vec4(own, 1.0);
}
