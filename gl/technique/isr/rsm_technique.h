// `rsm` and `rsm-full`: the reflective-shadow-map baselines of Nichols, Shopf & Wyman 2009 (after
// Dachsbacher & Stamminger 2005): RSM, VPLs on a regular grid of it (every texel for rsm-full), and a
// full-screen gather at every pixel (Eqs. 1-5). No indirect visibility.
#pragma once

#include "gl/technique/technique.h"

namespace bounce::gl {

TechniqueInfo rsmTechniqueInfo();
TechniqueInfo rsmFullTechniqueInfo();

} // namespace bounce::gl
