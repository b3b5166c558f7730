#version 450 core
// The G-buffer decoded through its accessors (common/gbuffer.glsl) into an RGBA32F target, for tests and
// tools (Frame::readPositions, readNormals): what every shader sees.
#include "common/gbuffer.glsl"

uniform int decodeNormals; // 0: world position and 1 where there is geometry; 1: normal and eye depth

layout(location = 0) out vec4 outValue;

void main()
{
    GSurface s = gbufferSurface(ivec2(gl_FragCoord.xy));
    if (!s.geometry)
        outValue = vec4(0.0);
    else
        outValue = decodeNormals != 0 ? vec4(s.normal, s.eyeDepth) : vec4(s.position, 1.0);
}
