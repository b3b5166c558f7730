#version 450 core
// One level of the RSM pyramid (common/rsm.glsl): the light-space depth and normal min-max
// mipmaps of §3.4, plus the sums from which a patch becomes one VPL (flux, lit solid angle and area,
// area-weighted centroid and mean normal). Level `level` + 1 from level `level`, every layer at once.
#include "common/rsm.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(rgba32f, binding = 0) uniform image2DArray position;
layout(rgba32f, binding = 1) uniform image2DArray normal;
layout(rgba32f, binding = 2) uniform image2DArray flux;
layout(rg32f, binding = 3) uniform image2DArray depthRange;
layout(rgba16f, binding = 4) uniform image2DArray normalMin;
layout(rgba16f, binding = 5) uniform image2DArray normalMax;

uniform int size;   // level-0 size of a layer
uniform int level;  // the source level; this pass writes level + 1

void main()
{
    int dstSize = size >> (level + 1);
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    int layer = int(gl_GlobalInvocationID.z);
    if (q.x >= dstSize || q.y >= dstSize) return;

    float count = 0.0, litArea = 0.0, omega = 0.0;
    vec3 centroidLit = vec3(0.0), centroidAll = vec3(0.0), normalLit = vec3(0.0), normalAll = vec3(0.0);
    vec3 fluxSum = vec3(0.0);
    vec2 dr = vec2(1e30, 0.0);
    vec3 nMin = vec3(2.0), nMax = vec3(-2.0);
    for (int i = 0; i < 4; ++i) {
        ivec3 c = ivec3(rsmAtlasTexel(2 * q + ivec2(i & 1, i >> 1), level, size), layer);
        vec4 p = imageLoad(position, c);
        vec4 n = imageLoad(normal, c);
        vec4 f = imageLoad(flux, c);
        vec2 d = imageLoad(depthRange, c).xy;
        count += p.w;
        centroidAll += p.w * p.xyz;
        normalAll += p.w * n.xyz;
        centroidLit += n.w * p.xyz;
        normalLit += n.w * n.xyz;
        litArea += n.w;
        fluxSum += f.rgb;
        omega += f.w;
        dr = vec2(min(dr.x, d.x), max(dr.y, d.y));
        nMin = min(nMin, imageLoad(normalMin, c).xyz);
        nMax = max(nMax, imageLoad(normalMax, c).xyz);
    }
    vec3 patchCentre = litArea > 0.0 ? centroidLit / litArea : (count > 0.0 ? centroidAll / count : vec3(0.0));
    vec3 meanNormal = litArea > 0.0 ? normalLit : normalAll;
    float len = length(meanNormal);
    meanNormal = len > 0.0 ? meanNormal / len : vec3(0.0);

    ivec3 dst = ivec3(rsmAtlasTexel(q, level + 1, size), layer);
    imageStore(position, dst, vec4(patchCentre, count));
    imageStore(normal, dst, vec4(meanNormal, litArea));
    imageStore(flux, dst, vec4(fluxSum, omega));
    imageStore(depthRange, dst, vec4(dr, 0.0, 0.0));
    imageStore(normalMin, dst, vec4(nMin, 0.0));
    imageStore(normalMax, dst, vec4(nMax, 0.0));
}
