// Point projection's binding points for C++: glsl/technique/pointproj/bindings.glsl as it is (the point
// cloud's are in gl/technique/points/bindings.h).
#pragma once

#include "glsl/technique/pointproj/bindings.glsl"
#include "glsl/technique/points/bindings.glsl"
