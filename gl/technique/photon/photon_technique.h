// `photon`: Wang, Wang, Zhou, Pan & Bao 2009, "An Efficient GPU-based Approach for Interactive Global
// Illumination": photon tracing (photon_tracer), a photon tree (photon_tree) and its illumination cut
// (illumination_cut), k-means shading clusters (shading_clusters), final gather at the clusters' samples
// and interpolation to every pixel (final_gather). README.md maps the paper to the files.
#pragma once

#include "gl/technique/technique.h"

namespace bounce::gl {

TechniqueInfo photonTechniqueInfo();

} // namespace bounce::gl
