#version 450 core
// Counts the invocations of a dispatch: each one inside `size` adds 1 to its own cell, each one outside
// adds 1 to one counter (the dispatch helper's test, tests/gl/query_test.cpp).
layout(local_size_x = LOCAL_X, local_size_y = LOCAL_Y, local_size_z = LOCAL_Z) in;

layout(std430, binding = 0) buffer Cells { uint outside; uint cells[]; };
uniform ivec3 size;

void main()
{
    const ivec3 id = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(id, size))) {
        atomicAdd(outside, 1u);
        return;
    }
    atomicAdd(cells[(id.z * size.y + id.y) * size.x + id.x], 1u);
}
