#version 450 core
// One ray per fragment of a batchWidth-wide viewport, row by row (raycast_batch.glsl).
#include "frame/raycast_batch.glsl"

uniform int batchWidth;
layout(location = 0) out vec4 outColor;

void main()
{
    uint i = uint(gl_FragCoord.y) * uint(batchWidth) + uint(gl_FragCoord.x);
    if (i < rayCount) castBatchRay(i);
    outColor = vec4(0.0);
}
