// The Utah teapot (Martin Newell, 1975; public-domain data): its 32 bicubic Bezier patches tessellated
// into triangles. A curved, self-occluding, partly open mesh (the rim and the lid do not meet, the spout
// is open) that the project makes itself, for ray-casting tests and benchmarks.
#pragma once

#include "core/scene.h"

namespace bounce::core {

// The teapot in metres, y up, standing on y = 0 and about 0.6 m wide (the data's 1 unit = 0.1 m), each
// patch cut into segments x segments quads (two triangles each; patches that close at a pole give one
// degenerate triangle per pole quad). Vertices shared by neighbouring patches are welded, so a ray
// through a seam meets the same float coordinates from both sides. Vertex normals are the area-weighted
// face normals.
Mesh makeTeapot(int segments = 8, std::uint32_t material = 0);

// The teapot alone (a Lambertian grey and one point light above it), with a camera that frames it.
Scene makeTeapotScene(int segments = 8);

} // namespace bounce::core
