// The storage names and binding points of the frame's buffers and textures, for C++:
// glsl/common/bindings.glsl is included as it is, so that the numbers exist once for both languages (SSBO_*,
// UNIT_*). Bind with the names, never with literal numbers (tests/gl/bindings_test.cpp checks the shaders and
// the frame's C++).
#pragma once

#include "glsl/common/bindings.glsl"
