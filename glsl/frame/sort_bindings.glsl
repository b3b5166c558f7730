// Storage names of the frame's scan and radix sort (gl/frame/gpu_sort.h; scan_*.comp, radix_*.comp), for
// GLSL and C++ alike (gl/frame/gpu_sort.cpp includes this file): 30-39 (glsl/common/bindings.glsl). GpuScan
// and RadixSort bind their buffers under these names for each call; a pass of a family that writes a scan's
// data may declare it under SSBO_SCAN. Only #define lines and comments.
#ifndef BOUNCE_SORT_BINDINGS_GLSL
#define BOUNCE_SORT_BINDINGS_GLSL

#define SSBO_SCAN_TOTALS 30 // scan_blocks.comp: counters[totalSlot] := the scan's total
#define SSBO_SCAN 31        // scan_*.comp: the array a prefix sum runs over, in place
#define SSBO_SORT_KEYS 32   // radix_*.comp: keys and values in, then out (ping-pong)
#define SSBO_SORT_VALUES 33
#define SSBO_SORT_KEYS_OUT 34
#define SSBO_SORT_VALUES_OUT 35
#define SSBO_SORT_COUNTS 36 // radix_*.comp: digit counts per run, scanned into offsets
#define SSBO_SCAN_SUMS 37   // scan_*.comp: the block sums of every level of a scan

#endif
