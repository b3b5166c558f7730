#version 450 core
// Depth peeling's last step per layer: the smallest texel at the layer's depth (a float value, from MIN
// blending) back into the k-buffer's entry format (texel + 1 as bits, depth), 0 where nothing was peeled;
// written to the k-buffer's layer and to the copy the next layer's pass reads.
#include "technique/grb/bindings.glsl"
layout(binding = UNIT_GRB_KBUFFER) uniform sampler2D peeled; // r: texel + 1 as a float, g: depth; r = 3e38: none
layout(location = 0) out vec4 outLayer;
layout(location = 1) out vec4 outPrevious;
void main()
{
    vec2 e = texelFetch(peeled, ivec2(gl_FragCoord.xy), 0).rg;
    vec4 entry = e.x < 1e38 ? vec4(uintBitsToFloat(uint(e.x)), e.y, 0.0, 0.0) : vec4(0.0);
    outLayer = entry;
    outPrevious = entry;
}
