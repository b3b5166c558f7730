#version 450 core
// Depth only: the shadow views store hardware depth compared with sampler2DArrayShadow. With
// ALPHA_MASK (scenes that have masked materials), light passes through a mask's holes.
#ifdef ALPHA_MASK
#include "common/scene.glsl"
#include "common/base_color.glsl"
in vec2 vUv;
flat in uint vMaterial;
void main()
{
    Material m = materials[vMaterial];
    if (alphaCutOut(m, baseColorTexel(m, vUv).a)) discard;
}
#else
void main() {}
#endif
