// `pointproj`: importance-driven point projection for GPU-based final gathering (Maletz, Wang & Bowers
// 2011). The shared lit point cloud (gl/frame/points/), 512 equal clusters of it (its median-split
// order), a gather kernel per shading pixel (projection_gather.h) at the pixels the image-space adaptive
// sampling of §3.3 picks (gl/frame/points/adaptive_pixels.h). Progressive by default (§3.3, "Progressive
// Rendering"): every frame draws new random points and adds its image to the running mean, until the
// scene, a light or the camera moves. One bounce; bounces > 1 gathers at the points first (§4).
#pragma once

#include "gl/technique/technique.h"

namespace bounce::gl {

TechniqueInfo pointprojTechniqueInfo();

} // namespace bounce::gl
