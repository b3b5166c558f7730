// Triangle adjacency for GL_TRIANGLES_ADJACENCY: per triangle of `indices` (three each) six indices, its
// corners at 0, 2 and 4 and after each edge (0-2, 2-4, 4-0) the corner, opposite that edge, of the one other
// triangle that shares it. Triangles share an edge when its two corners are at the same positions (bitwise),
// whatever their indices: meshes split their vertices at seams of normals or uvs, and across meshes. Where no
// other triangle or more than one shares an edge (the surface's boundary, a non-manifold edge), the slot
// holds the triangle's own opposite corner: a geometry shader tells a boundary by that. Passes that find
// silhouettes and creases read it (gl/frame/edge_antialias.h).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::core {

std::vector<std::uint32_t> triangleAdjacency(const std::vector<glm::vec3>& positions,
                                             const std::vector<std::uint32_t>& indices);

} // namespace bounce::core
