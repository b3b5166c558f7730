// The photon family's binding points for C++: glsl/technique/photon/bindings.glsl as it is, so that the
// numbers exist once (the frame's own are in gl/frame/bindings.h), after the frame's scan and sort slots
// that it names its data in.
#pragma once

#include "glsl/frame/sort_bindings.glsl"
#include "glsl/technique/photon/bindings.glsl"
