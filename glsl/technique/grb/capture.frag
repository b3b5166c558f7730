#version 450 core
// One fragment = one hit point: (atlas texel + 1, depth) into the k-buffer (Sec. 4.2, Fig. 4).
//   CAPTURE_STENCIL: written as colour; the stencil routes it to its sample (kbuffer.cpp).
//   CAPTURE_ATOMIC: the pixel's counter gives the slot; slots beyond KBUFFER_K are only counted.
//   CAPTURE_PEEL: one depth layer in two passes: PEEL_DEPTH keeps the nearest depth beyond the previous
//     layer (depth test LESS), PEEL_TEXEL the smallest texel at exactly that depth (depth test EQUAL, MIN
//     blending of the texel as a float, exact below 2^24): "beyond" orders by (depth, texel), so that
//     fragments at one depth (both faces of an edge seen edge-on) are peeled one by one.
//   CAPTURE_COUNT: only counts (the depth complexity that k=auto measures).
//   CAPTURE_OVERFLOW: peel's last pass, marks pixels with a layer beyond the last.
// ALPHA_MASK (a scene with masked materials): a fragment in a mask's hole is no hit; the ray goes on.
#include "technique/grb/bindings.glsl"

in vec2 vAtlas;
in float vDepth;
#ifdef ALPHA_MASK
#define SCENE_GEOMETRY
#include "common/scene.glsl"
#include "common/base_color.glsl"
flat in uint vTriangle;
in vec2 vUv;
#endif

uniform int atlasWidth;
uniform float depthScale; // 1 / (2 radius): gl_FragDepth for the peel's depth test

#if defined(CAPTURE_ATOMIC) || defined(CAPTURE_COUNT)
layout(r32ui, binding = 0) uniform coherent uimage2D kbufferCounter;
#endif
#if defined(CAPTURE_ATOMIC)
layout(rg32f, binding = 1) uniform writeonly image2DArray kbufferSlots;
#endif
#if defined(CAPTURE_PEEL) || defined(CAPTURE_OVERFLOW)
layout(binding = UNIT_GRB_KBUFFER) uniform sampler2D previousLayer; // a copy: never the layer drawn into
uniform int firstLayer;                                           // 1: nothing to peel beyond
#endif

#if defined(CAPTURE_STENCIL) || defined(CAPTURE_PEEL)
layout(location = 0) out vec4 outEntry;
#elif defined(CAPTURE_OVERFLOW)
layout(location = 0) out uvec4 outOverflow;
#endif

void main()
{
#ifdef ALPHA_MASK
    Material m = materials[sceneTriangleMaterial(vTriangle)];
    if (intBitsToFloat(m.flags.z) > 0.0 && alphaCutOut(m, baseColorTexel(m, vUv).a)) discard;
#endif
    ivec2 t = ivec2(floor(vAtlas));
    vec4 entry = vec4(uintBitsToFloat(uint(t.y) * uint(atlasWidth) + uint(t.x) + 1u), vDepth, 0.0, 0.0);
#if defined(CAPTURE_ATOMIC)
    uint slot = imageAtomicAdd(kbufferCounter, ivec2(gl_FragCoord.xy), 1u);
    if (slot < uint(KBUFFER_K)) imageStore(kbufferSlots, ivec3(ivec2(gl_FragCoord.xy), int(slot)), entry);
#elif defined(CAPTURE_COUNT)
    imageAtomicAdd(kbufferCounter, ivec2(gl_FragCoord.xy), 1u);
#elif defined(CAPTURE_STENCIL)
    outEntry = entry;
#else
    if (firstLayer == 0) {
        vec2 prev = texelFetch(previousLayer, ivec2(gl_FragCoord.xy), 0).rg;
        uint prevTexel = floatBitsToUint(prev.x), texel = floatBitsToUint(entry.x);
        // Nothing beyond an empty layer; beyond means after (depth, texel) in lexicographic order.
        if (prevTexel == 0u || vDepth < prev.y || (vDepth == prev.y && texel <= prevTexel)) discard;
    }
    gl_FragDepth = clamp(vDepth * depthScale, 0.0, 1.0);
#if defined(CAPTURE_PEEL)
    outEntry = vec4(float(floatBitsToUint(entry.x)), vDepth, 0.0, 0.0);
#else
    outOverflow = uvec4(1u);
#endif
#endif
}
