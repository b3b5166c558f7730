#version 450 core
// The illumination cut's irradiance (technique/photon/cut_lookup.glsl) at points from a buffer, for the
// test of the cut's accuracy against a brute-force density estimate on the CPU.
#include "technique/photon/cut_lookup.glsl"

layout(local_size_x = 64) in;

struct Query {
    vec4 position;
    vec4 normal;
};
layout(std430, binding = 0) readonly buffer Queries { Query queries[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform uint queryCount;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= queryCount) return;
    CutLookup c = cutIrradiance(queries[i].position.xyz, queries[i].normal.xyz);
    results[i] = vec4(c.irradiance, float(c.coverage));
}
