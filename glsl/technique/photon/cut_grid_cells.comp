#version 450 core
// The cut grid (cut_grid.glsl), steps 1 and 3, one invocation per heap slot: a cut node adds one to the
// count of every cell its kernel box reaches (counts, scanned in place into starts), or with FILL writes
// its index into each of those cells' lists, at the cell's start plus a cursor (in any order:
// cut_grid_sort.comp orders them). At most cutGridCells() cells per node: within llvmpipe's 65,535
// iterations of an invocation's loops for grids of up to 32^3 cells.
#include "technique/photon/illumination_cut.glsl"
#include "technique/photon/cut_grid.glsl"
#include "technique/photon/linear_dispatch.glsl"

layout(local_size_x = 64) in;

#ifdef FILL
layout(std430, binding = SSBO_CUT_GRID_CURSORS) buffer Cursors { uint cursors[]; };
#endif

uniform uint nodeCount;

void main()
{
    uint i = linearInvocation();
    if (i == 0u || i >= nodeCount || (cutFlags(i) & kCutIn) == 0u) return;
    vec4 cr = cutNodes[i].centreRadius;
    ivec3 lo = cutGridCellOf(cr.xyz - cr.w), hi = cutGridCellOf(cr.xyz + cr.w);
    for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x) {
                uint c = cutGridIndex(ivec3(x, y, z));
#ifdef FILL
                uint at = cutGrid[c] + atomicAdd(cursors[c], 1u);
                if (at < cutGridCapacity) cutGrid[cutGridEntryWord(at)] = i;
#else
                atomicAdd(cutGrid[c], 1u);
#endif
            }
}
