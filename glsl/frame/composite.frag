#version 450 core
// What the viewer sees: direct light plus the technique's indirect light.
#include "common/bindings.glsl"
layout(binding = UNIT_COMPOSITE_DIRECT) uniform sampler2D directLight;
layout(binding = UNIT_COMPOSITE_INDIRECT) uniform sampler2D indirectLight;
layout(location = 0) out vec4 outRadiance;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    outRadiance = vec4(texelFetch(directLight, px, 0).rgb + texelFetch(indirectLight, px, 0).rgb, 1.0);
}
