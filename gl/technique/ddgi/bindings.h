// The ddgi family's binding points for C++: glsl/technique/ddgi/bindings.glsl as it is, so that the numbers
// exist once (the frame's own are in gl/frame/bindings.h).
#pragma once

#include "glsl/technique/ddgi/bindings.glsl"
