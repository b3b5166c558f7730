// One index per invocation of a dispatch of groups of 64 laid out in rows (dispatchLinear in
// gl/technique/photon/photon_tree.h, gl/resource/dispatch.h's dispatchRows), so that a pass over millions
// of nodes stays within GL_MAX_COMPUTE_WORK_GROUP_COUNT. The including shader declares local_size_x = 64.
#ifndef BOUNCE_LINEAR_DISPATCH_GLSL
#define BOUNCE_LINEAR_DISPATCH_GLSL

#include "common/dispatch_rows.glsl"

uint linearInvocation() { return rowGroup() * 64u + gl_LocalInvocationIndex; }

#endif
