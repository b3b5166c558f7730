// Storage names of the shared lit point cloud (gl/frame/points/), which micro-rendering and point
// projection build on, for GLSL and C++ alike (gl/frame/points/bindings.h includes this file): 40-59
// (glsl/common/bindings.glsl). Only #define lines and comments.
#ifndef BOUNCE_POINTS_BINDINGS_GLSL
#define BOUNCE_POINTS_BINDINGS_GLSL

#define SSBO_POINT_SAMPLES 40  // point_cloud.glsl: (triangle, barycentrics, area) per point, in cloud order
#define SSBO_POINT_SURFELS 41  //   position, area, normal, diffuse colour per point (point_update.comp)
#define SSBO_POINT_RADIANCE 42 //   outgoing radiance per point, half floats (point_light.comp, point_relight.comp)
#define SSBO_POINT_DIRECT 43   //   the direct part alone, half floats (bounces > 1)
#define SSBO_POINT_GATHERED 44 //   diffuse light gathered at every stride-th point (bounces > 1)
#define SSBO_GATHER_TARGETS 45 // gather_target.glsl: how many texels to gather at (8 bytes), then the texels
#define SSBO_POINT_GLOSSY 47   //   what each point's glossy lobe needs (GLOSSY_POINTS)
// median_split.comp, for the length of a re-clustering (MedianSplit), beside the frame's scan and sort
// (glsl/frame/sort_bindings.glsl): the positions, the three sorted lists in and out, each point's half, the
// samples in the new order.
#define SSBO_MEDIAN_POSITIONS 50
#define SSBO_MEDIAN_LISTS 51
#define SSBO_MEDIAN_LISTS_OUT 52
#define SSBO_MEDIAN_SIDE 53
#define SSBO_MEDIAN_SAMPLES_OUT 54

#endif
