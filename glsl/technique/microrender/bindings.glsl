// Storage names (140-159) of micro-rendering's own buffers (gl/technique/microrender/bindings.h includes
// this file), beside the point cloud's (glsl/frame/points/bindings.glsl). Only #define lines and comments.
#ifndef BOUNCE_MICRORENDER_BINDINGS_GLSL
#define BOUNCE_MICRORENDER_BINDINGS_GLSL

#define SSBO_MICRO_NODES 140       // hierarchy.glsl: the complete binary point hierarchy, heap order
#define SSBO_MICRO_WARP_TABLES 141 // warp.glsl: the per-lobe warp tables
#define SSBO_MICRO_STATS 142       // gather.comp: counters of the last gather

#endif
