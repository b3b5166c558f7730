#version 450 core
// Counts the work groups of a dispatch in rows (gl/resource/dispatch.h: dispatchRows): each group inside
// `groups` adds 1 to its own cell, each one past it 1 to one counter (tests/gl/dispatch_test.cpp).
#include "common/dispatch_rows.glsl"

layout(local_size_x = 1) in;

layout(std430, binding = 0) buffer Cells { uint outside; uint cells[]; };
uniform uint groups;

void main()
{
    uint g = rowGroup();
    if (g >= groups) {
        atomicAdd(outside, 1u);
        return;
    }
    atomicAdd(cells[g], 1u);
}
