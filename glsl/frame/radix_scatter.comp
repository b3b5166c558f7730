#version 450 core
// The scatter of one radix pass: invocation r walks its run in order and moves each (key, value) to the
// next slot of its digit. Runs are contiguous and walked in order, so equal digits keep their order: the
// sort is stable, and sorting by several keys is sorting by the least significant one first.
#include "frame/radix_pass.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = SSBO_SORT_VALUES) readonly buffer Values { uint values[]; };
layout(std430, binding = SSBO_SORT_KEYS_OUT) writeonly buffer KeysOut { uint keysOut[]; };
layout(std430, binding = SSBO_SORT_VALUES_OUT) writeonly buffer ValuesOut { uint valuesOut[]; };
layout(std430, binding = SSBO_SORT_COUNTS) readonly buffer Counts { uint counts[]; };

void main()
{
    uint r = gl_GlobalInvocationID.x;
    if (r >= runs) return;
    uint next[16];
    for (uint d = 0u; d < 16u; ++d) next[d] = counts[d * runs + r];
    uint begin = r * runLength, end = min(begin + runLength, count);
    for (uint i = begin; i < end; ++i) {
        uint k = keys[i];
        uint d = radixDigit(k);
        uint slot = next[d];
        next[d] = slot + 1u;
        keysOut[slot] = k;
        valuesOut[slot] = values[i];
    }
}
