// The registry: every technique of Bounce, in the order `bounce list` shows them. A family adds a line
// here (an explicit table rather than static registration, which static libraries silently drop).
#include "gl/technique/ddgi/ddgi_technique.h"
#include "gl/technique/direct.h"
#include "gl/technique/grb/grb_technique.h"
#include "gl/technique/isr/hisr_technique.h"
#include "gl/technique/isr/isr_technique.h"
#include "gl/technique/isr/multires_technique.h"
#include "gl/technique/isr/rsm_technique.h"
#include "gl/technique/microrender/microrender_technique.h"
#include "gl/technique/photon/photon_technique.h"
#include "gl/technique/pointproj/pointproj_technique.h"
#include "gl/technique/technique.h"

namespace bounce::gl {

const std::vector<TechniqueInfo>& techniques()
{
    static const std::vector<TechniqueInfo> all = [] {
        std::vector<TechniqueInfo> t;
        t.push_back(directTechniqueInfo());
        t.push_back(rsmTechniqueInfo());
        t.push_back(rsmFullTechniqueInfo());
        t.push_back(multiresGatherTechniqueInfo());
        t.push_back(multiresSplatTechniqueInfo());
        t.push_back(isrTechniqueInfo());
        t.push_back(hisrTechniqueInfo());
        t.push_back(grbTechniqueInfo());
        t.push_back(photonTechniqueInfo());
        t.push_back(microrenderTechniqueInfo());
        t.push_back(pointprojTechniqueInfo());
        t.push_back(ddgiTechniqueInfo());
        return t;
    }();
    return all;
}

} // namespace bounce::gl
