#version 450 core
// The frame's direct light (common/lighting.glsl, addDirectLight) at every pixel's surface, lit twice in a
// compute shader built as every consumer of the estimator is (gl/frame/direct_lit_program.h): from the
// G-buffer's point, normal and BRDF, as frame/direct.frag lights it, and at the hit of a ray cast from the
// camera to that point through the frame's BVH, decoded from the scene (common/scene_hit.glsl) as the
// gathers decode their hits. For tests/gl/direct_estimator_test.cpp.
#define SCENE_GEOMETRY
#include "common/gbuffer.glsl"
#include "common/lighting.glsl"
#include "common/scene_hit.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
// Slots no program of this test's binds otherwise (common/bindings.glsl leaves 7 and 9 to techniques).
layout(std430, binding = 7) writeonly buffer AsPixel { vec4 asPixel[]; };  // emission + light, as direct.frag
layout(std430, binding = 9) writeonly buffer Lit { vec4 lit[]; };         // xyz: the G-buffer point's light
layout(std430, binding = 11) writeonly buffer AtHits { vec4 atHits[]; };  // xyz: the hit's light; w: 1 hit
uniform ivec2 size;
uniform vec3 cameraPosition;
uniform vec2 areaRotation;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, size))) return;
    uint i = uint(px.y * size.x + px.x);
    asPixel[i] = lit[i] = atHits[i] = vec4(0.0);
    GSurface s = gbufferSurface(px);
    if (!s.geometry) return;
    BrdfParams b = gbufferBrdf(px);
    vec3 wo = normalize(cameraPosition - s.position);
    vec3 radiance = gbufferEmission(px);
    addDirectLight(radiance, s.position, s.normal, wo, b, areaRotation);
    asPixel[i] = vec4(radiance, 1.0);
    vec3 light = vec3(0.0);
    addDirectLight(light, s.position, s.normal, wo, b, areaRotation);
    lit[i] = vec4(light, 1.0);

    vec3 d = s.position - cameraPosition;
    float t = length(d);
    d /= t;
    Hit hit;
    if (!closestHit(cameraPosition, d, 0.0, t * 1.001, hit)) return;
    SceneHit h = sceneHit(hit);
    vec3 n = h.n;
    if (dot(h.ng, d) > 0.0) {
        if (h.m.flags.y == 0) return; // the back of a one-sided surface: black, as the G-buffer has it
        n = -n;
    }
    vec3 atHit = vec3(0.0);
    addDirectLight(atHit, h.p, n, -d, h.b, areaRotation);
    atHits[i] = vec4(atHit, 1.0);
}
