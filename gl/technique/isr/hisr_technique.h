// `hisr`: hierarchical image-space radiosity (Nichols, Shopf & Wyman 2009, §3.5): the RSM at full
// resolution reorganised each frame into a VPL tree; every multiresolution fragment of the stenciled
// gather (§3.2) walks the tree and refines clusters by the bound of Eqs. 6-8.
#pragma once

#include "core/scene.h"
#include "gl/frame/gpu_scene.h"
#include "gl/technique/technique.h"

namespace bounce::gl {

TechniqueInfo hisrTechniqueInfo();

// I of Eq. 8: the largest intensity of any light of the frame, in W/sr, the largest RGB channel (spot and
// point lights: their intensity; an area light: sum of radiance x area over its triangles, the peak of
// its cosine lobe; a directional light: its irradiance in W/m^2, which has no W/sr reading).
double hisrPeakIntensity(const std::vector<LightSource>& lights);
// Invocations of the compute gather that share one fragment (gatherLanes=auto) for a gather of this
// many valid fragments: a power of two from 1 to 16, the most that keep the dispatch at 2^17 invocations.
int hisrGatherLanes(unsigned fragments);
// Eq. 8's per-frame constant T = 2 (I - tau) / (3 tau RSM_res^2); +inf for tau <= 0 (always refine).
double hisrRefineConstant(double peakIntensity, double tau, int rsmSize);

} // namespace bounce::gl
