#version 450 core
// Reads the scene's geometry through glsl/common/scene.glsl (SCENE_GEOMETRY), for the test that checks
// it against core::Scene: per triangle its three corners, its material, the point and normal at fixed
// barycentrics; then the emissive triangles.
#define SCENE_GEOMETRY
#include "common/scene.glsl"

layout(local_size_x = 64) in;

// Storage names of the test's own (tests/gl/gpu_scene_test.cpp binds them), apart from the scene's.
#define SSBO_TEST_TRIANGLES 1010
#define SSBO_TEST_EMITTERS 1011
layout(std430, binding = SSBO_TEST_TRIANGLES) writeonly buffer Triangles { vec4 triangleOut[]; }; // 6 vec4 per triangle
layout(std430, binding = SSBO_TEST_EMITTERS) writeonly buffer Emitters { vec4 emitterOut[]; };    // 1 + count
uniform vec2 barycentrics;

void main()
{
    uint t = gl_GlobalInvocationID.x;
    if (t == 0u) {
        emitterOut[0] = vec4(float(emissiveCount), emissiveTotalPowerW, float(sceneTriangleCount()), 0.0);
        for (uint i = 0u; i < emissiveCount; ++i) {
            EmissiveTriangle e = emissiveTriangles[i];
            emitterOut[1u + i] = vec4(float(e.triangle), float(e.material), e.areaM2, e.powerCdf);
        }
    }
    if (t >= sceneTriangleCount()) return;
    for (int k = 0; k < 3; ++k) triangleOut[6u * t + uint(k)] = vec4(sceneVertexPosition(sceneVertexIndex(t, k)), 0.0);
    triangleOut[6u * t + 3u] = vec4(float(sceneTriangleMaterial(t)), 0.0, 0.0, 0.0);
    triangleOut[6u * t + 4u] = vec4(sceneTrianglePoint(t, barycentrics), 0.0);
    triangleOut[6u * t + 5u] = vec4(sceneTriangleNormal(t, barycentrics), 0.0);
}
