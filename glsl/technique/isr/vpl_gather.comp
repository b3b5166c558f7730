#version 450 core
// Full-screen gather (Nichols, Shopf & Wyman 2009, §3.2.2, Eqs. 1 and 5, without the multiresolution
// stencil): every pixel sums the contributions of the vplCount VPLs of the bound block of the VPL cache
// (vpl.glsl: vplBlock; one dispatch per block). Writes (or, with accumulate, adds to) the frame's
// indirect radiance.
#include "common/gbuffer.glsl"
#include "technique/isr/vpl.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(rgba32f, binding = 0) uniform image2D indirectOut;

uniform ivec2 outputSize;
uniform int vplCount;
uniform int accumulate;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= outputSize.x || px.y >= outputSize.y) return;
    GSurface s = gbufferSurface(px);
    vec3 p = s.position;
    vec3 n = s.normal;
    vec3 rho = gbufferDiffuse(px).rgb;
    vec3 sum = vec3(0.0);
    if (s.geometry && max(rho.r, max(rho.g, rho.b)) > 0.0)
        for (int k = 0; k < vplCount; ++k) sum += vplContribution(vplBlock[k], p, n, rho);
    if (accumulate != 0) sum += imageLoad(indirectOut, px).rgb;
    imageStore(indirectOut, px, vec4(sum, 1.0));
}
