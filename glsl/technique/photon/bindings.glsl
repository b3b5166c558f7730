// Binding points of the photon family's own buffers (Wang, Wang, Zhou, Pan & Bao 2009), for GLSL and C++
// alike (gl/technique/photon/bindings.h includes this file), in the slots glsl/common/bindings.glsl leaves
// to techniques. Only #define lines and comments.
#ifndef BOUNCE_PHOTON_BINDINGS_GLSL
#define BOUNCE_PHOTON_BINDINGS_GLSL

#define SSBO_PHOTON_EMITTERS 7       // photon_trace.comp: one PhotonEmitter per light, with its photon range
// photon.glsl: the family's counters and per-frame scalars, the scans' totals among them: the slot of the
// frame's scan totals (glsl/frame/sort_bindings.glsl, whose slots 17 and 22-26 the family leaves to the
// scan and the sort)
#define SSBO_PHOTON_COUNTERS 8
#define SSBO_PHOTON_STAGING 9        // photon_trace.comp: photons as traced (any order); the sort's spare
#define SSBO_PHOTON_PATHS 11         // photon_trace.comp: photons stored per path, scanned into offsets
#define SSBO_PHOTON_EMITTED 12       // photon_trace.comp: each path's emitted power
#define SSBO_PHOTONS 13              // photon.glsl: the photons in Morton order
#define SSBO_PHOTON_NODES 14         // photon_tree.glsl: the photon tree, one PhotonNode per node
#define SSBO_PHOTON_CUT 15           // illumination_cut.glsl: per node: cut state, generation, E_p
#define SSBO_PHOTON_CUT_LIST 16      // illumination_cut.glsl: lists of cut nodes (the coarse cut, those entering it)
// cut_grid.glsl: the cut grid, its cell starts scanned in place as a scan's data, read by the gather
// after the cut's scans; its fill's cursors in the sort's slot, free while it is built.
#define SSBO_CUT_GRID SSBO_SCAN
#define SSBO_CUT_GRID_CURSORS SSBO_SORT_KEYS
#define SSBO_CLUSTER_QUADTREE 27     // shading_clusters.glsl: the screen-space quadtree's nodes
#define SSBO_CLUSTER_CENTRES 28      // shading_clusters.glsl: centres, members and samples of the clusters
#define SSBO_CLUSTER_OF_PIXEL 29     // shading_clusters.glsl: each shading point's cluster
#define SSBO_POINT_TREE 30           // point_tree.glsl: a tree over points (cluster centres, samples)
#define SSBO_CLUSTER_SEEDS 31        // shading_clusters.glsl: seeds per quadtree node, then seed pixels
#define UNIT_PHOTON_CELLS 21         // photon_trace.comp: the directional lights' projection-map cells (R32UI texels)

#endif
