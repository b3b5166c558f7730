// glTF normal maps (core::Material::normalTexture) at a surface point: the shading normal bent by the
// tangent-space normal of the material's map. The G-buffer pass reads it under NORMAL_MAPS, which its
// program gets only for a scene that has normal maps (gl/frame/gpu_scene.h) and the frame parameter
// normalMaps on (gl/frame/frame.cpp, gbufferProgram); the path tracer bends its normals with the same
// formula (ref/embree_scene.cpp: EmbreeScene::surface), so that the two stay comparable.
#ifndef BOUNCE_NORMAL_MAP_GLSL
#define BOUNCE_NORMAL_MAP_GLSL

#include "common/bindings.glsl"
layout(binding = UNIT_NORMAL_MAP) uniform sampler2DArray normalTextures;

// n (unit, the interpolated vertex normal) bent by the map: the tangent made orthogonal to n (Gram-Schmidt),
// the bitangent sign(w) cross(n, t), and the map's texel m = 2 texel - 1 with x and y times the scale,
// n' = normalize(m.x t + m.y b + m.z n). n as it is where the material has no map (map.x < 0), the mesh no
// tangent (zero) or the tangent lies along n.
vec3 normalMapped(vec3 n, vec4 tangent, ivec4 map, vec2 uv)
{
    if (map.x < 0) return n;
    vec3 t = tangent.xyz - n * dot(n, tangent.xyz);
    float t2 = dot(t, t);
    if (!(t2 > 1e-12)) return n;
    t *= inversesqrt(t2);
    vec3 b = cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
    vec3 m = textureLod(normalTextures, vec3(uv, float(map.x)), 0.0).xyz * 2.0 - 1.0;
    m.xy *= intBitsToFloat(map.y);
    vec3 bent = m.x * t + m.y * b + m.z * n;
    float len2 = dot(bent, bent);
    return len2 > 1e-12 ? bent * inversesqrt(len2) : n;
}

#endif
