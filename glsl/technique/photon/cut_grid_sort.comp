#version 450 core
// The cut grid (cut_grid.glsl), step 4, one invocation per cell: its list sorted into depth-first order
// (cutDepthFirstKey), the order of the tree walk's sum, by heapsort (2 n log2 n steps at most: a list of
// up to kMaxSorted stays within llvmpipe's 65,535 loop iterations per invocation). A longer list, or lists
// past the capacity, mark the grid unusable, and the lookups walk the tree.
#include "frame/sort_bindings.glsl"
#include "technique/photon/bindings.glsl"
#include "technique/photon/cut_grid.glsl"
#include "technique/photon/linear_dispatch.glsl"

layout(local_size_x = 64) in;

const uint kMaxSorted = 2048u;

uint keyAt(uint base, uint k) { return cutDepthFirstKey(cutGrid[base + k]); }

// Moves entry k of the heap of words [base, base + n) down to where both its children's keys are below its own.
void siftDown(uint base, uint k, uint n)
{
    uint v = cutGrid[base + k], key = cutDepthFirstKey(v);
    for (uint child = 2u * k + 1u; child < n; child = 2u * k + 1u) {
        if (child + 1u < n && keyAt(base, child + 1u) > keyAt(base, child)) ++child;
        uint c = cutGrid[base + child];
        if (cutDepthFirstKey(c) <= key) break;
        cutGrid[base + k] = c;
        k = child;
    }
    cutGrid[base + k] = v;
}

void main()
{
    uint c = linearInvocation();
    uint cells = cutGridCells();
    if (c >= cells || cutGrid[cells] > cutGridCapacity) return;
    uint base = cutGridEntryWord(cutGrid[c]), n = cutGrid[c + 1u] - cutGrid[c];
    if (n > kMaxSorted) {
        cutGrid[cells + 1u] = 1u;
        return;
    }
    for (uint k = n / 2u; k > 0u; --k) siftDown(base, k - 1u, n);
    for (uint end = n; end > 1u; --end) {
        uint top = cutGrid[base];
        cutGrid[base] = cutGrid[base + end - 1u];
        cutGrid[base + end - 1u] = top;
        siftDown(base, 0u, end - 1u);
    }
}
