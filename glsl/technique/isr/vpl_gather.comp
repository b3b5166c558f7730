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
    vec4 pos = texelFetch(gPosition, px, 0);
    vec3 p = pos.xyz;
    vec3 n = texelFetch(gNormal, px, 0).xyz;
    vec3 rho = texelFetch(gDiffuse, px, 0).rgb;
    vec3 sum = vec3(0.0);
    if (pos.w != 0.0 && max(rho.r, max(rho.g, rho.b)) > 0.0)
        for (int k = 0; k < vplCount; ++k) sum += vplContribution(vplBlock[k], p, n, rho);
    if (accumulate != 0) sum += imageLoad(indirectOut, px).rgb;
    imageStore(indirectOut, px, vec4(sum, 1.0));
}
