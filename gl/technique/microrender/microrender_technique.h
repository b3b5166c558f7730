// `microrender`: micro-rendering for scalable, parallel final gathering (Ritschel, Engelhardt, Grosch,
// Seidel, Kautz & Dachsbacher 2009). The shared lit point cloud (gl/frame/points/), its point hierarchy
// rebuilt every frame (point_hierarchy.h), and one gather kernel per gather sample (micro_gather.h) at a
// subset of the pixels chosen by the frame's multiresolution pyramid and upsampled (gl/frame/points/pixel_gather.h).
// One bounce with visibility; bounces > 1 gathers at the points first (§4, a Jacobi iteration).
#pragma once

#include "gl/technique/technique.h"

namespace bounce::gl {

TechniqueInfo microrenderTechniqueInfo();

} // namespace bounce::gl
