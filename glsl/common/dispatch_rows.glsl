// The work group of a one-dimensional dispatch laid out in rows (gl/resource/dispatch.h: dispatchRows):
// groups along x, at most 65,535 to a row, the least GL_MAX_COMPUTE_WORK_GROUP_COUNT a driver may have
// per axis, and as many rows (y) as it takes. The last row's groups past the count run too: the shader
// returns early there. An invocation's index is rowGroup() times the local size plus
// gl_LocalInvocationIndex (the local size is the including shader's: gl_WorkGroupSize may not be read
// before its declaration, and this file may come first).
#ifndef BOUNCE_DISPATCH_ROWS_GLSL
#define BOUNCE_DISPATCH_ROWS_GLSL

uint rowGroup() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

#endif
