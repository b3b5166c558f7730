#version 450 core
// Probe: triangle setup rate. A grid of `side` x `side` cells over the viewport, two attribute-less
// triangles per cell, each about `cellPixels` pixels; what a dense mesh costs before any shading.
uniform int side;
void main()
{
    const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
    int cell = gl_VertexID / 6;
    vec2 c = (vec2(cell % side, cell / side) + corners[gl_VertexID % 6]) / float(side);
    gl_Position = vec4(c * 2.0 - 1.0, 0.0, 1.0);
}
