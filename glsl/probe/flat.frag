#version 450 core
// Probe: the cheapest fragment shader (triangle setup, framebuffer writes).
uniform vec4 colour;
layout(location = 0) out vec4 outValue;
void main()
{
    outValue = colour;
}
