#version 450 core
// Regular-grid VPL sampling of the RSM (Dachsbacher & Stamminger 2005, the baseline of Nichols et al.
// 2009 §3.2.2): each view is cut into side x side blocks of texels and each block becomes one VPL of the
// VPL cache (technique/isr/vpl_write.glsl: blockVpl). With side = the RSM size every texel is a VPL.
#include "technique/isr/vpl_write.glsl"

layout(local_size_x = 64) in;

uniform int rsmSize;
uniform int side;       // VPLs per view and per side
uniform int viewCount;
uniform float level;    // log2 of the block's side in texels

void main()
{
    int index = int(gl_GlobalInvocationID.x);
    int perView = side * side;
    if (index >= perView * viewCount) return;
    int view = index / perView, cell = index % perView;
    ivec2 b = ivec2(cell % side, cell / side);
    // Integer partition: blocks differ by at most one texel when side does not divide the size.
    ivec2 lo = b * rsmSize / side, hi = (b + 1) * rsmSize / side;
    outVpls[index] = blockVpl(view, lo, hi, level);
}
