#version 450 core
// One colour: the query tests only count fragments.
layout(location = 0) out vec4 colour;

void main() { colour = vec4(1.0); }
