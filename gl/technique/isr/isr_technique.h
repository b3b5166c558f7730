// `isr`: basic image-space radiosity (Nichols, Shopf & Wyman 2009, §3.4): RSM with its light-space
// min-max pyramid, VPLs formed per frame by clustering RSM texels at several resolutions (isr_cluster),
// gathered by the stenciled multiresolution gather of §3.2 (multires_gather; or at every pixel with
// multires=0). Eye-space parameters as multires-gather's; light-space ones prefixed "light".
#pragma once

#include "gl/technique/technique.h"

namespace bounce::gl {

TechniqueInfo isrTechniqueInfo();

} // namespace bounce::gl
