// The screen-space quadtree over the clusters' error that the seeds are placed over (section 3.2;
// gl/technique/photon/shading_clusters.h, buildQuadtree).
#ifndef BOUNCE_CLUSTER_QUADTREE_GLSL
#define BOUNCE_CLUSTER_QUADTREE_GLSL

#include "technique/photon/shading_clusters.glsl"

// The screen-space quadtree: level 0 is the pixels of a square of side quadSize (the viewport padded to a
// power of two), level m has (quadSize >> m)^2 nodes; levels are stored one after the other.
struct QuadNode {
    vec4 position; // xyz summed member positions, w: members
    vec4 normal;   // xyz summed member normals, w: eps_q, the summed Eq. 2 error of its members to their mean
};

layout(std430, binding = SSBO_CLUSTER_QUADTREE) buffer Quadtree { QuadNode quadNodes[]; };

uniform int quadSize;
uniform int quadLevels; // levels above the pixels: the root is level quadLevels

uint quadOffset(int level)
{
    // sum over m < level of (quadSize >> m)^2
    uint offset = 0u;
    for (int m = 0; m < level; ++m) offset += uint((quadSize >> m) * (quadSize >> m));
    return offset;
}
uint quadIndex(int level, ivec2 q) { return quadOffset(level) + uint(q.y * (quadSize >> level) + q.x); }

#endif
