#version 450 core
// technique/ddgi/probes.glsl's octahedral texels, for tests/gl/ddgi_test.cpp: per direction of a spherical
// Fibonacci set (and the six axes), where a lookup reads it in probe `probe`'s tile (octAtlasTexel), and
// where the direction of the texel it falls in (octTexelDirection) reads in turn.
#include "technique/ddgi/probes.glsl"
#include "technique/ddgi/rays.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 7) writeonly buffer Out { vec4 result[]; }; // xy: d's texel coordinate, zw: its texel's

uniform int count;  // Fibonacci directions; six axes follow them
uniform int probe;
uniform int inner;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= count + 6) return;
    vec3 d = i < count ? sphericalFibonacci(i, count) : vec3(0.0);
    if (i >= count) d[(i - count) % 3] = (i - count) < 3 ? 1.0 : -1.0;
    vec2 at = octAtlasTexel(probe, d, inner);
    ivec2 texel = ivec2(floor(at)) - probeTile(probe, inner + 2) - 1;
    result[i] = vec4(at, octAtlasTexel(probe, octTexelDirection(clamp(texel, 0, inner - 1), inner), inner));
}
