// `ddgi`: Majercik, Guertin, Nowrouzezahrai & McGuire 2019, "Dynamic Diffuse Global Illumination with
// Ray-Traced Irradiance Fields" (JCGT 8(2)), with probe relocation and classification from Majercik,
// Marrs, Spjut & McGuire 2021 (JCGT 10(2)): a grid of irradiance probes with visibility, updated by rays
// each frame and blended with hysteresis (probe_field). README.md maps the papers to the files.
#pragma once

#include "gl/technique/technique.h"

namespace bounce::gl {

TechniqueInfo ddgiTechniqueInfo();

} // namespace bounce::gl
