// `grb`: global ray-bundles (Hermes, Henrich, Grosch & Mueller 2010; README.md in this folder): for each
// direction of a Halton sequence the scene is captured along parallel rays into a k-buffer of atlas
// texels, and every atlas texel receives Eq. 3 from its neighbour along the ray; sender and receiver
// atlases swap after each direction (interleaved bounces), a glossy transfer atlas carries glossy
// paths, punctual lights seed the first bounce through the shadow maps. Progressive.
#pragma once

#include "gl/technique/technique.h"

namespace bounce::gl {

TechniqueInfo grbTechniqueInfo();

} // namespace bounce::gl
