// One level of the photon tree per dispatch, one invocation per node of it, in rows of 64 (the bottom-up
// passes: tree_reduce.comp, cut_select.comp, cut_influence.comp).
#ifndef BOUNCE_PHOTON_TREE_LEVEL_GLSL
#define BOUNCE_PHOTON_TREE_LEVEL_GLSL

#include "technique/photon/linear_dispatch.glsl"
layout(local_size_x = 64) in;

uniform int level;

// This invocation's node of the level (heap index, photon_tree.glsl), or 0 past the level's last node.
uint levelNode()
{
    uint k = linearInvocation();
    return k < (1u << uint(level)) ? (1u << uint(level)) + k : 0u;
}

#endif
