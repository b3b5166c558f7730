// Binding points of the frame's scan and radix sort (gl/frame/gpu_sort.h; scan_*.comp, radix_*.comp), for
// GLSL and C++ alike (gl/frame/gpu_sort.cpp includes this file). They are slots glsl/common/bindings.glsl
// leaves to techniques, bound for the length of a call: a family that uses the primitives names its data in
// these slots (the photon family's counters take the scan's totals) or binds its own again after a call.
// Only #define lines and comments.
#ifndef BOUNCE_SORT_BINDINGS_GLSL
#define BOUNCE_SORT_BINDINGS_GLSL

#define SSBO_SCAN_TOTALS 8          // scan_blocks.comp: counters[totalSlot] := the scan's total
#define SSBO_SCAN 17                // scan_*.comp: the array a prefix sum runs over, in place
#define SSBO_SORT_KEYS 22           // radix_*.comp: keys and values in, then out (ping-pong)
#define SSBO_SORT_VALUES 23
#define SSBO_SORT_KEYS_OUT 24
#define SSBO_SORT_VALUES_OUT 25
#define SSBO_SORT_COUNTS 26         // radix_*.comp: digit counts per run, scanned into offsets
// scan_*.comp: the block sums of every level of a scan. Every slot is taken, so the scan borrows the
// sort's counts slot: nothing reads that slot across a scan but the sort, which binds it again after.
#define SSBO_SCAN_SUMS SSBO_SORT_COUNTS

#endif
