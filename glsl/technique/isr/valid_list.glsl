// The valid fragments a compute gather runs over (multires_valid_list.comp lists them), and the flattened
// buffer it adds its light into: each invocation owns one texel, whose alpha keeps the stencil pass's marks.
#ifndef BOUNCE_VALID_LIST_GLSL
#define BOUNCE_VALID_LIST_GLSL

#include "common/dispatch_rows.glsl"
#include "technique/isr/bindings.glsl"

// Groups of 64 along x (MultiresGather::gather's group count).
layout(local_size_x = 64) in;

layout(rgba32f, binding = 0) uniform image2D illumination;
layout(std430, binding = SSBO_ISR_VALID_LIST) readonly buffer ValidList { uint validCount; uint validFragments[]; };

// Fragment i of the list; false past its end.
bool listedFragmentAt(uint i, out ivec2 at)
{
    at = ivec2(0);
    if (i >= validCount) return false;
    at = ivec2(validFragments[i] & 0xFFFFu, validFragments[i] >> 16);
    return true;
}

// This invocation's index: the dispatch is laid out in rows (MultiresGather::gather: dispatchRows).
uint listInvocation() { return rowGroup() * gl_WorkGroupSize.x + gl_LocalInvocationIndex; }

// This invocation's fragment of the flattened buffer; false past the end of the list.
bool listedFragment(out ivec2 at) { return listedFragmentAt(listInvocation(), at); }

// Adds to what earlier dispatches gathered at the fragment (the gather may be split over several).
void addToFragment(ivec2 at, vec3 light)
{
    vec4 old = imageLoad(illumination, at);
    imageStore(illumination, at, vec4(old.rgb + light, old.a));
}

#endif
