// The point families' binding points for C++: glsl/frame/points/bindings.glsl as it is, so that the
// numbers exist once (the frame's own are in gl/frame/bindings.h).
#pragma once

#include "glsl/frame/points/bindings.glsl"
