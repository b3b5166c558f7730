// Storage names (120-139), uniform block and texture unit of image-space radiosity's own buffers, for GLSL
// and C++ alike (gl/technique/isr/bindings.h includes this file); the slots are those
// glsl/common/bindings.glsl leaves to techniques. Only #define lines and comments.
#ifndef BOUNCE_ISR_BINDINGS_GLSL
#define BOUNCE_ISR_BINDINGS_GLSL

#define UBO_ISR_VPL_BLOCK 0          // vpl.glsl: one block of the VPL cache per gather draw
#define SSBO_ISR_CLUSTER_SLOTS 120   // isr_cluster*.comp: emit marks, then their prefix sums
#define SSBO_ISR_VPL_CACHE 121       // vpl_write.glsl: the VPL cache written by sampling and clustering
#define SSBO_ISR_VPL_COUNT 122       // isr_cluster.comp: VPLs written, per level
#define SSBO_ISR_FRAGMENT_COUNTS 123 // multires_refine.comp: valid fragments per level (the stencil pass counts by queries)
#define SSBO_ISR_VPL_TREE 124        // vpl_tree_*.comp: the VPL tree's nodes
#define SSBO_ISR_TREE_STATS 125      // hisr_gather.frag: VPLs gathered and fragments
#define SSBO_ISR_WORK_IN 126         // multires_refine.comp: patches to test at this level
#define SSBO_ISR_WORK_OUT 127        //   and their children for the next
#define SSBO_ISR_REFINE_COUNTS 128
#define SSBO_ISR_SPLAT_VERTICES 129
#define SSBO_ISR_VALID_LIST 130      // multires_valid_list.comp: the valid fragments, for a compute gather
#define UNIT_ISR_VPL_TREE_TEXELS 21  // hisr_gather.frag: the VPL tree as a buffer texture

#endif
