// `multires-gather`: the stencil-based multiresolution gather of Nichols, Shopf & Wyman 2009, §3.2, with
// the VPLs of the `rsm` baseline (a reflective shadow map sampled on a regular grid): RSM -> VPL cache ->
// eye-space min-max pyramid -> one stencil pass -> one stenciled gather -> upsample.
#pragma once

#include "gl/technique/isr/multires_gather.h"
#include "gl/technique/technique.h"

namespace bounce::gl {

TechniqueInfo multiresGatherTechniqueInfo();
// `multires-splat`: [NW09]'s multiresolution splatting, the path §3.2 replaces (the paper's Table 1):
// RSM -> VPL cache -> eye-space min-max pyramid -> iterative refinement -> per-VPL point splats -> upsample.
TechniqueInfo multiresSplatTechniqueInfo();

} // namespace bounce::gl
