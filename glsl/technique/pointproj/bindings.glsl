// Storage names (200-219) of importance-driven point projection's own buffers
// (gl/technique/pointproj/bindings.h includes this file), beside the point cloud's
// (glsl/frame/points/bindings.glsl). Only #define lines and comments.
#ifndef BOUNCE_POINTPROJ_BINDINGS_GLSL
#define BOUNCE_POINTPROJ_BINDINGS_GLSL

#define SSBO_PROJ_TEXEL_SOLID_ANGLES 200 // gather.comp: the hemi-octahedral micro-buffer's texel solid angles
#define SSBO_PROJ_STATS 201              // gather.comp: counters of the last gather

#endif
