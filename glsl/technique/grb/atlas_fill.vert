#version 450 core
// The static atlases (Sec. 4.1), drawn once per scene: each triangle as the quad of its bounding box in
// the atlas grown by the fill margin (core::fillQuad), six vertices per triangle pulled from the corners.
#define SCENE_GEOMETRY
#include "common/scene.glsl"
#include "technique/grb/atlas.glsl"

uniform vec2 atlasSize;   // texels
uniform float fillMargin; // core::kFillMargin

flat out uint vTriangle;

void main()
{
    uint t = uint(gl_VertexID) / 6u;
    int v = gl_VertexID % 6;
    vec2 a = atlasCorner(t, 0), b = atlasCorner(t, 1), c = atlasCorner(t, 2);
    vec2 lo = min(a, min(b, c)) - fillMargin, hi = max(a, max(b, c)) + fillMargin;
    // Two triangles: (lo, (hi.x, lo.y), hi) and (lo, hi, (lo.x, hi.y)).
    const ivec2 corner[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));
    vec2 q = mix(lo, hi, vec2(corner[v]));
    vTriangle = t;
    gl_Position = vec4(q / atlasSize * 2.0 - 1.0, 0.0, 1.0);
}
