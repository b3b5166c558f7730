// Micro-rendering's binding points for C++: glsl/technique/microrender/bindings.glsl as it is (the point
// cloud's are in gl/frame/points/bindings.h).
#pragma once

#include "glsl/frame/points/bindings.glsl"
#include "glsl/technique/microrender/bindings.glsl"
