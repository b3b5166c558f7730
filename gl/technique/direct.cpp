#include "gl/technique/direct.h"

namespace bounce::gl {

namespace {
class Direct final : public Technique {
public:
    void render(Frame&, PassTimers&) override {} // the frame's indirect texture stays zero
    bool readsShadowMaps(const Frame& /*frame*/) const override { return false; }
};
} // namespace

TechniqueInfo directTechniqueInfo()
{
    TechniqueInfo info;
    info.name = "direct";
    info.paper = "-";
    info.lightPaths = core::LightPaths::Direct;
    info.summary = "emission + direct light with shadow maps; the base every technique adds to";
    info.create = [](Frame&, const ParamValues&) { return std::make_unique<Direct>(); };
    return info;
}

} // namespace bounce::gl
