// GPU layouts of the scene shared by every pass (gl/frame/gpu_scene.h writes them, std430).
#ifndef BOUNCE_SCENE_GLSL
#define BOUNCE_SCENE_GLSL

struct Material {
    vec4 baseColorMetallic;       // rgb linear, metallic
    vec4 emissionRoughness;       // rgb W/(m^2 sr), roughness
    vec4 specularColorSpecular;   // rgb, specular factor
    ivec4 flags;                  // x: texture layer or -1, y: double-sided
};

const int kLightPoint = 0;
const int kLightSpot = 1;
const int kLightDirectional = 2;
const int kLightArea = 3;         // one emissive triangle: vertices in lightPolygons

struct Light {
    vec4 positionType;            // xyz position (area: centroid of its mesh), w: type
    vec4 directionCosOuter;       // xyz direction light travels (area: emitter normal), w: cos outer cone
    vec4 intensityCosInner;       // rgb W/sr (directional W/m^2, area radiance W/(m^2 sr)), w: cos inner cone
    ivec4 shadow;                 // x: first shadow layer (-1 none), y: layer count (1 or 6), z: first polygon vertex
};

struct ShadowView {
    mat4 viewProj;
    vec4 originFar;               // xyz light origin, w: far plane (perspective) or 0 (orthographic)
    vec4 texelWorld;              // x: world size of one texel at distance 1 (perspective) or absolute (ortho)
};

#ifndef SCENE_BINDINGS_CUSTOM
layout(std430, binding = 0) readonly buffer Materials { Material materials[]; };
layout(std430, binding = 1) readonly buffer Lights { Light lights[]; };
layout(std430, binding = 2) readonly buffer ShadowViews { ShadowView shadowViews[]; };
layout(std430, binding = 3) readonly buffer LightPolygons { vec4 lightPolygons[]; };
#endif

// Cube face of a direction, in the order +x, -x, +y, -y, +z, -z (the order of shadow layers).
int cubeFace(vec3 d)
{
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x > 0.0 ? 0 : 1;
    if (a.y >= a.z) return d.y > 0.0 ? 2 : 3;
    return d.z > 0.0 ? 4 : 5;
}

// glTF spot falloff (core::Light::spotWeight): t^2 between the cones, a step when they coincide.
float spotWeight(Light l, float cosAngle)
{
    float cosOuter = l.directionCosOuter.w, cosInner = l.intensityCosInner.w;
    if (cosInner - cosOuter < 1e-6) return cosAngle >= cosOuter ? 1.0 : 0.0;
    float t = clamp((cosAngle - cosOuter) / (cosInner - cosOuter), 0.0, 1.0);
    return t * t;
}

#endif
