// Storage names (160-199) and texture unit of the photon family's own buffers (Wang, Wang, Zhou, Pan & Bao
// 2009), for GLSL and C++ alike (gl/technique/photon/bindings.h includes this file); the unit is one
// glsl/common/bindings.glsl leaves to techniques. Only #define lines and comments.
#ifndef BOUNCE_PHOTON_BINDINGS_GLSL
#define BOUNCE_PHOTON_BINDINGS_GLSL

#define SSBO_PHOTON_EMITTERS 160  // photon_trace.comp: one PhotonEmitter per light, with its photon range
// photon.glsl: the family's counters and per-frame scalars, the scans' totals among them (the buffer the
// family hands GpuScan and RadixSort for their totals, which bind it as SSBO_SCAN_TOTALS)
#define SSBO_PHOTON_COUNTERS 161
#define SSBO_PHOTON_STAGING 162   // photon_trace.comp: photons as traced (any order)
#define SSBO_PHOTON_PATHS 163     // photon_trace.comp: photons stored per path, scanned into offsets
#define SSBO_PHOTON_EMITTED 164   // photon_trace.comp: each path's emitted power
#define SSBO_PHOTONS 165          // photon.glsl: the photons in Morton order
#define SSBO_PHOTON_NODES 166     // photon_tree.glsl: the photon tree, one PhotonNode per node
#define SSBO_PHOTON_CUT 167       // illumination_cut.glsl: per node: cut state, generation, E_p
#define SSBO_PHOTON_CUT_LIST 168  // illumination_cut.glsl: lists of cut nodes (the coarse cut, those entering it)
// cut_grid.glsl: the cut grid, its cell starts scanned in place (GpuScan binds it as its data), read by
// the gather after the cut's scans; and its fill's cursors.
#define SSBO_CUT_GRID 169
#define SSBO_CUT_GRID_CURSORS 170
#define SSBO_CLUSTER_QUADTREE 171 // cluster_quadtree.glsl: the screen-space quadtree's nodes
#define SSBO_CLUSTER_CENTRES 172  // shading_clusters.glsl: centres, members and samples of the clusters
#define SSBO_CLUSTER_OF_PIXEL 173 // shading_clusters.glsl: each shading point's cluster
#define SSBO_POINT_TREE 174       // cluster_point_tree.glsl: a tree over points (cluster centres, samples)
#define SSBO_CLUSTER_SEEDS 175    // shading_clusters.glsl: seeds per quadtree node, then seed pixels
#define UNIT_PHOTON_CELLS 21      // photon_trace.comp: the directional lights' projection-map cells (R32UI texels)

#endif
