#version 450 core
// target[i] := source[i] * factor, through storage blocks bound by name (tests/gl/storage_bindings_test.cpp):
// names far past any driver's count of binding points, which the program turns into its own points.
// TARGET_NAME (injected, always: a name must be defined once) picks the target's name; ONLY_TARGET leaves the
// source out (target[i] := factor).
layout(local_size_x = 64) in;

#define SSBO_TEST_SOURCE 1000
#define SSBO_TEST_TARGET 1001
#define SSBO_TEST_UNBOUND 1002

#ifndef ONLY_TARGET
layout(std430, binding = SSBO_TEST_SOURCE) readonly buffer Source { uint source[]; };
#endif
layout(std430, binding = TARGET_NAME) writeonly buffer Target { uint target[]; };
uniform uint count;
uniform uint factor;

void main()
{
    const uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
#ifdef ONLY_TARGET
    target[i] = factor;
#else
    target[i] = source[i] * factor;
#endif
}
