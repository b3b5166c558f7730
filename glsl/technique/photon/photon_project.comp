#version 450 core
// A projection map for a directional light (Jensen 1996, "Global illumination using photon maps"): the
// square its photons leave from, across the light and behind the scene, cut into gridSize^2 cells; each
// cell traces probesPerSide^2 rays along the light and is marked when one of them first meets a surface
// that takes light (its front, or either side of a two-sided one, and not an emitter). Photons then
// leave from marked cells only (photon_trace.comp), so that a sun over a large scene sends them where
// geometry receives them (PhotonTracer, which also widens the marks by a cell).
#define SCENE_GEOMETRY
#include "common/scene.glsl"
#include "common/raycast.glsl"
#include "technique/photon/photon.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SSBO_SCAN) writeonly buffer Marks { uint cellMarks[]; };

uniform vec3 corner;     // the square's corner on the emission plane
uniform vec3 axisU;      // unit axes of the square, across the light
uniform vec3 axisV;
uniform vec3 direction;  // the way light travels
uniform float cellSide;  // metres
uniform uint gridSize;
uniform uint probesPerSide;

void main()
{
    uint cell = gl_GlobalInvocationID.x;
    if (cell >= gridSize * gridSize) return;
    vec2 c = vec2(cell % gridSize, cell / gridSize);
    uint marked = 0u;
    for (uint k = 0u; k < probesPerSide * probesPerSide && marked == 0u; ++k) {
        vec2 f = (c + (vec2(k % probesPerSide, k / probesPerSide) + 0.5) / float(probesPerSide)) * cellSide;
        Hit hit;
        if (!closestHit(corner + f.x * axisU + f.y * axisV, direction, 0.0, 3.0e38, hit)) continue;
        uint tri = hit.triangle;
        vec3 p0 = sceneVertexPosition(sceneVertexIndex(tri, 0));
        vec3 p1 = sceneVertexPosition(sceneVertexIndex(tri, 1));
        vec3 p2 = sceneVertexPosition(sceneVertexIndex(tri, 2));
        Material m = materials[sceneTriangleMaterial(tri)];
        bool front = dot(cross(p1 - p0, p2 - p0), direction) < 0.0 || m.flags.y != 0;
        bool emits = max(m.emissionRoughness.r, max(m.emissionRoughness.g, m.emissionRoughness.b)) > 0.0;
        if (front && !emits) marked = 1u;
    }
    cellMarks[cell] = marked;
}
