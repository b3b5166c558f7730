// What the two passes of one radix-sort pass share (radix_count.comp, radix_scatter.comp; gl/frame/
// gpu_sort.h): the keys, their runs (invocation r takes the keys [r L, r L + L)) and the pass's digit.
#ifndef BOUNCE_RADIX_PASS_GLSL
#define BOUNCE_RADIX_PASS_GLSL

#include "frame/sort_bindings.glsl"

layout(std430, binding = SSBO_SORT_KEYS) readonly buffer Keys { uint keys[]; };

uniform uint count;     // keys
uniform uint runLength; // L
uniform uint runs;
uniform uint shift;     // the pass's digit: bits [shift, shift + 4) of a key

// A key's digit in this pass, 0 to 15.
uint radixDigit(uint key) { return (key >> shift) & 15u; }

#endif
