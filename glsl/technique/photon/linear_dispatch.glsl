// One index per invocation of a dispatch laid out in rows of kLinearRow invocations (dispatchLinear in
// gl/technique/photon/photon_tree.h), so that a pass over millions of nodes stays within
// GL_MAX_COMPUTE_WORK_GROUP_COUNT (65,535 groups per axis: about 4M invocations of 64).
#ifndef BOUNCE_LINEAR_DISPATCH_GLSL
#define BOUNCE_LINEAR_DISPATCH_GLSL

const uint kLinearRow = 1u << 21;

uint linearInvocation() { return gl_GlobalInvocationID.y * kLinearRow + gl_GlobalInvocationID.x; }

#endif
