// Binding points of the shared lit point cloud (gl/frame/points/) and of the two families built on it
// (micro-rendering, point projection), for GLSL and C++ alike (gl/frame/points/bindings.h includes
// this file), in the slots glsl/common/bindings.glsl leaves to techniques. Both families use these slots;
// each names its own in its bindings.glsl (15 and up). Only #define lines and comments.
#ifndef BOUNCE_POINTS_BINDINGS_GLSL
#define BOUNCE_POINTS_BINDINGS_GLSL

#define SSBO_POINT_SAMPLES 7         // point_cloud.glsl: (triangle, barycentrics, area) per point, in cloud order
#define SSBO_POINT_SURFELS 8         //   position, area, normal, diffuse colour per point (point_update.comp)
#define SSBO_POINT_RADIANCE 9        //   outgoing radiance per point, half floats (point_light.comp, point_relight.comp)
#define SSBO_POINT_DIRECT 11         //   the direct part alone, half floats (bounces > 1)
#define SSBO_POINT_GATHERED 12       //   diffuse light gathered at every stride-th point (bounces > 1)
#define SSBO_GATHER_TARGETS 13       // gather_target.glsl: the flattened-buffer texels to gather at
#define SSBO_GATHER_COUNT 14         //   how many
#define SSBO_POINT_GLOSSY 22         //   what each point's glossy lobe needs (GLOSSY_POINTS)
// median_split.comp, for the length of a re-clustering (MedianSplit), beside the frame's scan and sort
// (glsl/common/bindings.glsl): the positions, the three sorted lists in and out, each point's half, the
// samples in the new order. A family's slots of these numbers are bound again by its next pass.
#define SSBO_MEDIAN_POSITIONS 27
#define SSBO_MEDIAN_LISTS 28
#define SSBO_MEDIAN_LISTS_OUT 29
#define SSBO_MEDIAN_SIDE 30
#define SSBO_MEDIAN_SAMPLES_OUT 31

#endif
