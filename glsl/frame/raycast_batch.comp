#version 450 core
// One ray per invocation (raycast_batch.glsl).
#include "frame/raycast_batch.glsl"

layout(local_size_x = 64) in;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i < rayCount) castBatchRay(i);
}
