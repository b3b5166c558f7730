// The G-buffer every technique reads (gl/frame/frame.h: Frame::bindGBuffer), through the accessors below:
// no shader reads its textures directly, so that its layout can change in one place.
//
// Layout (what the scene needs and no more, DESIGN.md):
//   gGeometry  RG32UI   x: eye-space linear depth (m) as float bits, 0 where no geometry (background);
//                       y: the world shading normal, octahedral, 2 x 16-bit snorm (common/packing.glsl)
//   gDiffuse   RGBA16F  rgb c_diff, a: specular weight w
//   gSpecular  RGBA16F  rgb F0, a: roughness; only when a material has a glossy lobe (w > 0)
//   gEmission  RGBA16F  rgb emitted radiance; only when a material emits
// The world position is not stored: it is the camera position plus the eye depth along the pixel's ray
// (gbufferPosition; the G-buffer pass writes the depth where that ray meets the triangle's plane, see
// frame/gbuffer.frag), on the surface to float rounding, where an RGBA32F target cost 16 bytes per pixel
// to write and to read. A scene without glossy materials or emitters gets no specular or emission target: the frame
// binds a 1x1 black texture instead and gbufferCamera.present zeroes the fetch coordinates; programs
// compiled with Frame::gbufferDefines() (SCENE_DIFFUSE_ONLY, SCENE_NO_EMITTERS) do not fetch at all.
#ifndef BOUNCE_GBUFFER_GLSL
#define BOUNCE_GBUFFER_GLSL

#include "common/bindings.glsl"
#include "common/brdf.glsl"
#include "common/packing.glsl"

layout(binding = UNIT_G_GEOMETRY) uniform usampler2D gGeometry;
layout(binding = UNIT_G_DIFFUSE) uniform sampler2D gDiffuse;
layout(binding = UNIT_G_SPECULAR) uniform sampler2D gSpecular;
layout(binding = UNIT_G_EMISSION) uniform sampler2D gEmission;

// The camera that rendered the G-buffer (gl/frame/frame.cpp: GBufferCamera): the ray through the centre of
// pixel px is origin + t (corner + (px + 0.5).x axisX + (px + 0.5).y axisY), t the eye depth.
layout(std140, binding = UBO_GBUFFER_CAMERA) uniform GBufferCamera {
    vec4 origin;  // xyz camera position (m)
    vec4 corner;  // xyz: the forward axis less half the image along axisX and axisY
    vec4 axisX;   // xyz: one pixel to the right on the plane one metre ahead
    vec4 axisY;   // xyz: one pixel up
    ivec4 present; // x: 1 when gSpecular is a full-size target, y: the same for gEmission
} gbufferCamera;

bool gbufferHasGeometry(ivec2 px) { return texelFetch(gGeometry, px, 0).x != 0u; }
float gbufferEyeDepth(ivec2 px) { return uintBitsToFloat(texelFetch(gGeometry, px, 0).x); }
vec3 gbufferNormal(ivec2 px) { return unpackUnitVector(texelFetch(gGeometry, px, 0).y); }
// `precise`: no contraction into FMAs, so that a fragment and a compute shader (compiled apart) rebuild
// the very same position for the same pixel (photon mapping matches pixels to cluster samples exactly).
vec3 gbufferRay(ivec2 px)
{
    vec2 c = vec2(px) + 0.5;
    precise vec3 ray = gbufferCamera.corner.xyz + c.x * gbufferCamera.axisX.xyz + c.y * gbufferCamera.axisY.xyz;
    return ray;
}
vec3 gbufferPositionAt(ivec2 px, float eyeDepth)
{
    precise vec3 p = gbufferCamera.origin.xyz + eyeDepth * gbufferRay(px);
    return p;
}
vec3 gbufferPosition(ivec2 px) { return gbufferPositionAt(px, gbufferEyeDepth(px)); }

// What most passes need of a pixel at once, one fetch of gGeometry.
struct GSurface {
    bool geometry;   // false: background (the rest is undefined)
    float eyeDepth;  // m
    vec3 position;   // world (m)
    vec3 normal;     // world shading normal, unit
};
GSurface gbufferSurface(ivec2 px)
{
    uvec2 g = texelFetch(gGeometry, px, 0).xy;
    GSurface s;
    s.geometry = g.x != 0u;
    s.eyeDepth = uintBitsToFloat(g.x);
    s.position = gbufferPositionAt(px, s.eyeDepth);
    s.normal = unpackUnitVector(g.y);
    return s;
}

vec4 gbufferDiffuse(ivec2 px) { return texelFetch(gDiffuse, px, 0); } // rgb c_diff, a: specular weight w
vec4 gbufferSpecular(ivec2 px)                                            // rgb F0, a: roughness
{
#ifdef SCENE_DIFFUSE_ONLY
    return vec4(0.0);
#else
    return texelFetch(gSpecular, px * gbufferCamera.present.x, 0);
#endif
}
// The one BRDF's parameters at pixel px.
BrdfParams gbufferBrdf(ivec2 px)
{
    vec4 d = gbufferDiffuse(px);
    vec4 s = gbufferSpecular(px);
    BrdfParams b;
    b.diffuse = d.rgb;
    b.weight = d.a;
    b.f0 = s.rgb;
    b.alpha = max(s.a * s.a, 1e-3);
    return b;
}

vec3 gbufferEmission(ivec2 px)
{
#ifdef SCENE_NO_EMITTERS
    return vec3(0.0);
#else
    return texelFetch(gEmission, px * gbufferCamera.present.y, 0).rgb;
#endif
}

#endif
