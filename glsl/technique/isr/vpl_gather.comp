#version 450 core
// Full-screen gather (Nichols, Shopf & Wyman 2009, §3.2.2, Eqs. 1 and 5, without the multiresolution
// stencil): every pixel sums the contributions of VPLs [vplBegin, vplEnd) of the VPL cache. A work group
// of 8 x 8 pixels stages 64 VPLs at a time in shared memory, so each VPL is read from the cache once per
// group. Writes (or, with accumulate, adds to) the frame's indirect radiance.
#include "common/gbuffer.glsl"
#include "technique/isr/vpl.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(rgba32f, binding = 0) uniform image2D indirectOut;

uniform ivec2 outputSize;
uniform int vplBegin;
uniform int vplEnd;
uniform int accumulate;

shared Vpl tile[64];

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    bool inside = px.x < outputSize.x && px.y < outputSize.y;
    vec3 p = vec3(0.0), n = vec3(0.0), rho = vec3(0.0);
    bool shade = false;
    if (inside) {
        vec4 pos = texelFetch(gPosition, px, 0);
        p = pos.xyz;
        n = texelFetch(gNormal, px, 0).xyz;
        rho = texelFetch(gDiffuse, px, 0).rgb;
        shade = pos.w != 0.0 && max(rho.r, max(rho.g, rho.b)) > 0.0;
    }
    vec3 sum = vec3(0.0);
    int local = int(gl_LocalInvocationIndex);
    for (int base = vplBegin; base < vplEnd; base += 64) {
        int i = base + local;
        if (i < vplEnd) {
            tile[local] = vpls[i];
        } else {
            tile[local].positionArea = vec4(0.0, 0.0, 0.0, 1.0);
            tile[local].normal = vec4(0.0);
            tile[local].flux = vec4(0.0);
        }
        barrier();
        if (shade) {
            int count = min(64, vplEnd - base);
            for (int k = 0; k < count; ++k) sum += vplContribution(tile[k], p, n, rho);
        }
        barrier();
    }
    if (!inside) return;
    if (accumulate != 0) sum += imageLoad(indirectOut, px).rgb;
    imageStore(indirectOut, px, vec4(sum, 1.0));
}
