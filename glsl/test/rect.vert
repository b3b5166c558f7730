#version 450 core
// Attribute-less triangles for the query tests: vertex i of `rect` (x0, y0, x1, y1 in NDC) as two
// triangles per quad, quads repeated `quads` times side by side in instance order.
uniform vec4 rect;

void main()
{
    const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
    const vec2 c = corners[gl_VertexID % 6];
    gl_Position = vec4(mix(rect.xy, rect.zw, c), 0.0, 1.0);
}
