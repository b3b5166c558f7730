// A uniform grid over the illumination cut's kernels (cut_grid_cells.comp, cut_grid_sort.comp;
// gl/technique/photon/illumination_cut.h): per cell, the cut nodes whose kernel box (r_p around the
// centre, Eq. 5) reaches into it, in the order the walk of the tree above the cut meets them (depth-first).
// Eq. 4 at y then sums over y's cell's list instead of walking the tree: the same nodes in the same order,
// the same sum to the bit (not the paper's: section 3.3 walks the tree; cut_lookup.glsl says why).
#ifndef BOUNCE_CUT_GRID_GLSL
#define BOUNCE_CUT_GRID_GLSL

#include "frame/sort_bindings.glsl"
#include "technique/photon/bindings.glsl"

// One buffer (one storage block: the gather has no more to spare): the cells' starts (an exclusive scan
// of their counts, in place: cells + 1 words, the last the total), one word set when a cell's list was
// too long to sort, then the lists, one after another (cutGridEntryWord).
layout(std430, binding = SSBO_CUT_GRID) buffer CutGrid { uint cutGrid[]; };

uniform vec3 cutGridOrigin;
uniform float cutGridInverseCell; // 1 / the cells' side
uniform ivec3 cutGridDims;
uniform uint cutGridCapacity; // entries the lists may hold

uint cutGridCells() { return uint(cutGridDims.x * cutGridDims.y * cutGridDims.z); }
// Where entry a of the lists lies in the buffer.
uint cutGridEntryWord(uint a) { return cutGridCells() + 2u + a; }

// The cell holding p, clamped to the grid: monotonic in each coordinate, so a box's range of cells holds
// the cell of every point in the box, inside the grid or not (NaN: some cell, whose kernels it misses).
ivec3 cutGridCellOf(vec3 p)
{
    vec3 c = clamp(floor((p - cutGridOrigin) * cutGridInverseCell), vec3(-1.0), vec3(cutGridDims));
    return clamp(ivec3(c), ivec3(0), cutGridDims - 1);
}

uint cutGridIndex(ivec3 c) { return uint((c.z * cutGridDims.y + c.y) * cutGridDims.x + c.x); }

// Whether every cell's list was written and sorted: else the lookups walk the tree.
bool cutGridUsable()
{
    uint cells = cutGridCells();
    return cutGrid[cells] <= cutGridCapacity && cutGrid[cells + 1u] == 0u;
}

// A node's place in the depth-first walk of the heap (left child first): its index shifted up to bit 31.
// Unique among nodes of which none lies under another, as the cut's.
uint cutDepthFirstKey(uint i) { return i << (31 - findMSB(i)); }

#endif
