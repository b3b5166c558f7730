// `direct`: emission plus direct light with shadow maps, no indirect light. Every other technique
// adds indirect light to exactly this.
#pragma once

#include "gl/technique/technique.h"

namespace bounce::gl {

TechniqueInfo directTechniqueInfo();

} // namespace bounce::gl
