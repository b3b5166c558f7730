// GPU layouts of the scene shared by every pass (gl/frame/gpu_scene.h writes them, std430).
#ifndef BOUNCE_SCENE_GLSL
#define BOUNCE_SCENE_GLSL

// Still frames' shadow rays in a scene with alpha masks (common/shadow.glsl, RAY_SHADOWS) read the triangles'
// materials and uvs: the geometry comes with the scene whichever file includes this one first.
#if defined(RAY_SHADOWS) && defined(ALPHA_MASK) && !defined(SCENE_GEOMETRY)
#define SCENE_GEOMETRY
#endif

struct Material {
    vec4 baseColorMetallic;       // rgb linear, metallic
    vec4 emissionRoughness;       // rgb W/(m^2 sr), roughness
    vec4 specularColorSpecular;   // rgb, specular factor
    ivec4 flags;                  // x: texture layer or -1, y: double-sided, z: alpha cutoff (float bits,
                                  // 0 unless MASK), w: baseColorFactor alpha (float bits)
    ivec4 normalMap;              // x: normal texture layer or -1, y: its scale (float bits)
};

const int kLightPoint = 0;
const int kLightSpot = 1;
const int kLightDirectional = 2;
const int kLightArea = 3;         // one emissive triangle: vertices lightPolygon(shadow.z + 0..2)

// One light (gl/frame/frame_lights.h's GpuLight, the frame's records): frameLight(i).
struct Light {
    vec3 position;                // point, spot; area: the emitting mesh's point this frame (frame 0: its centroid)
    int type;                     // kLight*
    vec3 direction;               // the direction light travels (area: the emitter's normal)
    float cosOuter;               // spot: cos of the outer cone's half angle
    vec3 intensity;               // W/sr (directional W/m^2, area radiance W/(m^2 sr))
    float cosInner;               // spot: cos of the inner cone's half angle
    ivec4 shadow;                 // x: first shadow layer (-1 none), y: layer count (1 or 6), z: first polygon vertex
    float sampleArea;             // area, still frames: the mesh's area on the triangle holding the frame's point
};

// The view of one shadow layer: shadowView(layer).
struct ShadowView {
    mat4 viewProj;
    vec4 originFar;               // xyz light origin, w: far plane (perspective) or 0 (orthographic)
    vec4 texelWorld;              // x: world size of one texel at distance 1 (perspective) or absolute (ortho),
                                  // y: the share of the layer's side the view is rendered at (1: all of it)
};

#include "common/bindings.glsl"
layout(std430, binding = SSBO_MATERIALS) readonly buffer Materials { Material materials[]; };

// The frame's lights in one block (gl/frame/frame_lights.h has the layout): the header says where the
// shadow views (x) and the area lights' triangles (y) begin, in vec4s after it; the lights begin at 0.
layout(std430, binding = SSBO_LIGHTS) readonly buffer FrameLights {
    ivec4 frameLightsAt;
    vec4 frameLightData[];
};

Light frameLight(int i)
{
    int o = 5 * i;
    vec4 a = frameLightData[o], b = frameLightData[o + 1], c = frameLightData[o + 2];
    Light l;
    l.position = a.xyz;
    l.type = floatBitsToInt(a.w);
    l.direction = b.xyz;
    l.cosOuter = b.w;
    l.intensity = c.xyz;
    l.cosInner = c.w;
    l.shadow = floatBitsToInt(frameLightData[o + 3]);
    l.sampleArea = frameLightData[o + 4].x;
    return l;
}

ShadowView shadowView(int layer)
{
    int o = frameLightsAt.x + 6 * layer;
    ShadowView v;
    v.viewProj = mat4(frameLightData[o], frameLightData[o + 1], frameLightData[o + 2], frameLightData[o + 3]);
    v.originFar = frameLightData[o + 4];
    v.texelWorld = frameLightData[o + 5];
    return v;
}

// Vertex k of the area lights' triangles (a light's first is its shadow.z).
vec3 lightPolygon(int k) { return frameLightData[frameLightsAt.y + k].xyz; }

// The scene's geometry, for shaders that define SCENE_GEOMETRY before including this file (gl/frame/
// gpu_scene.h, GpuVertex and GpuEmissiveTriangle, writes them): the rasteriser's own vertex and index
// buffers read as std430 arrays, and the emissive triangles with their power CDF. Triangle t is the t-th
// triangle of the scene's meshes in order, as in core::Scene, the BVH and the path tracer.
#ifdef SCENE_GEOMETRY
layout(std430, binding = SSBO_SCENE_VERTICES) readonly buffer SceneVertices { float sceneVertexData[]; };
layout(std430, binding = SSBO_SCENE_INDICES) readonly buffer SceneIndices { uint sceneIndices[]; };
struct EmissiveTriangle {
    uint triangle;
    uint material;
    float areaM2;
    float powerCdf;               // cumulative share of emitted power up to and including this triangle
};
layout(std430, binding = SSBO_SCENE_EMISSIVE) readonly buffer SceneEmissive {
    uint emissiveCount;
    float emissiveTotalPowerW;    // pi L A summed over the emitters (luminance)
    uint emissivePad0, emissivePad1;
    EmissiveTriangle emissiveTriangles[];
};

const int kSceneVertexFloats = 9;  // position xyz, normal xyz, uv, material bits

uint sceneTriangleCount() { return uint(sceneIndices.length()) / 3u; }
uint sceneVertexIndex(uint triangle, int corner) { return sceneIndices[3u * triangle + uint(corner)]; }
vec3 sceneVertexPosition(uint v)
{
    uint o = v * uint(kSceneVertexFloats);
    return vec3(sceneVertexData[o], sceneVertexData[o + 1u], sceneVertexData[o + 2u]);
}
vec3 sceneVertexNormal(uint v)
{
    uint o = v * uint(kSceneVertexFloats) + 3u;
    return vec3(sceneVertexData[o], sceneVertexData[o + 1u], sceneVertexData[o + 2u]);
}
vec2 sceneVertexUv(uint v)
{
    uint o = v * uint(kSceneVertexFloats) + 6u;
    return vec2(sceneVertexData[o], sceneVertexData[o + 1u]);
}
// Every vertex of a mesh carries the mesh's material: the triangle's is its first vertex's.
uint sceneTriangleMaterial(uint triangle)
{
    return floatBitsToUint(sceneVertexData[sceneVertexIndex(triangle, 0) * uint(kSceneVertexFloats) + 8u]);
}
// The point at barycentrics (b1, b2) of a triangle (b0 = 1 - b1 - b2), and its interpolated unit normal.
vec3 sceneTrianglePoint(uint triangle, vec2 b)
{
    return (1.0 - b.x - b.y) * sceneVertexPosition(sceneVertexIndex(triangle, 0)) +
           b.x * sceneVertexPosition(sceneVertexIndex(triangle, 1)) + b.y * sceneVertexPosition(sceneVertexIndex(triangle, 2));
}
// The triangle's area as the vertices are now, m^2.
float sceneTriangleArea(uint triangle)
{
    vec3 p0 = sceneVertexPosition(sceneVertexIndex(triangle, 0));
    return 0.5 * length(cross(sceneVertexPosition(sceneVertexIndex(triangle, 1)) - p0,
                              sceneVertexPosition(sceneVertexIndex(triangle, 2)) - p0));
}
vec3 sceneTriangleNormal(uint triangle, vec2 b)
{
    vec3 n = (1.0 - b.x - b.y) * sceneVertexNormal(sceneVertexIndex(triangle, 0)) +
             b.x * sceneVertexNormal(sceneVertexIndex(triangle, 1)) + b.y * sceneVertexNormal(sceneVertexIndex(triangle, 2));
    float len = length(n);
    return len > 0.0 ? n / len : vec3(0.0, 0.0, 1.0);
}
vec2 sceneTriangleUv(uint triangle, vec2 b)
{
    return (1.0 - b.x - b.y) * sceneVertexUv(sceneVertexIndex(triangle, 0)) +
           b.x * sceneVertexUv(sceneVertexIndex(triangle, 1)) + b.y * sceneVertexUv(sceneVertexIndex(triangle, 2));
}
#endif

// How far a ray leaves a surface point p along its normal so that it does not hit p's own triangle again:
// 2e-4 of p's largest coordinate (float rounding grows with it), at least 0.2 mm. The frame's shadow rays
// (common/shadow.glsl) and micro-rendering's gather point (technique/microrender/gather.comp) take it.
float surfaceRayOffset(vec3 p) { return 2e-4 * max(max(abs(p.x), abs(p.y)), max(abs(p.z), 1.0)); }

// Cube face of a direction, in the order +x, -x, +y, -y, +z, -z (the order of shadow layers).
int cubeFace(vec3 d)
{
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x > 0.0 ? 0 : 1;
    if (a.y >= a.z) return d.y > 0.0 ? 2 : 3;
    return d.z > 0.0 ? 4 : 5;
}

// glTF spot falloff (core::Light::spotWeight): t^2 between the cones, a step when they coincide. Of the
// cones' cosines, for a spot that is not a Light record (photon_trace.comp's emitters), and of a Light.
float spotWeight(float cosOuter, float cosInner, float cosAngle)
{
    if (cosInner - cosOuter < 1e-6) return cosAngle >= cosOuter ? 1.0 : 0.0;
    float t = clamp((cosAngle - cosOuter) / (cosInner - cosOuter), 0.0, 1.0);
    return t * t;
}
float spotWeight(Light l, float cosAngle)
{
    return spotWeight(l.cosOuter, l.cosInner, cosAngle);
}

#endif
