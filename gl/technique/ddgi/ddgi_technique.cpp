#include "gl/technique/ddgi/ddgi_technique.h"

#include <memory>

#include "gl/technique/ddgi/probe_field.h"

namespace bounce::gl {

namespace {

class Ddgi final : public Technique {
public:
    Ddgi(const Frame& frame, const ProbeFieldSettings& s) : field_(frame, s) {}

    void render(Frame& frame, PassTimers& timers) override
    {
        field_.update(frame, timers);
        field_.shade(frame, timers);
    }

    std::vector<Counter> counters() const override
    {
        const ProbeGrid& g = field_.grid();
        double active = 0.0, moved = 0.0;
        for (const glm::vec4& s : field_.probeStates()) {
            active += s.w != 0.0f ? 1.0 : 0.0;
            moved += (s.x != 0.0f || s.y != 0.0f || s.z != 0.0f) ? 1.0 : 0.0;
        }
        return {
            {"probes", double(g.probes())},   {"probes.x", double(g.counts.x)},
            {"probes.y", double(g.counts.y)}, {"probes.z", double(g.counts.z)},
            {"probes.active", active},        {"probes.relocated", moved},
            {"rays", field_.raysPerFrame()},  {"updates", double(field_.updates())},
        };
    }

private:
    ProbeField field_;
};

} // namespace

TechniqueInfo ddgiTechniqueInfo()
{
    TechniqueInfo info;
    info.name = "ddgi";
    info.paper = "Majercik, Guertin, Nowrouzezahrai & McGuire 2019; Majercik, Marrs, Spjut & McGuire 2021";
    // Full on diffuse scenes; it carries no glossy interreflection (README.md: cornell-glossy's error).
    info.lightPaths = core::LightPaths::Full;
    info.summary = "dynamic diffuse GI: a grid of irradiance probes with distance moments, updated by rays "
                   "through the BVH each frame with hysteresis, shaded with Chebyshev visibility";
    info.passes = {
        {"probe-trace",
         "rays from every probe through the BVH, lit at their hits by the frame's direct light and "
         "last frame's probes",
         ""},
        {"probe-state",
         "probe relocation out of solids and classification (inactive probes skipped), from the "
         "fixed rays",
         "relocation or classification"},
        {"probe-update",
         "the rays blended into the octahedral irradiance and distance-moment atlases, borders "
         "included, with hysteresis",
         ""},
        {"shade",
         "every pixel's irradiance from its eight probes with Chebyshev visibility, reflected by the "
         "diffuse lobe",
         ""},
    };
    info.reads = {GBufferChannel::Position, GBufferChannel::Normal, GBufferChannel::Diffuse, GBufferChannel::Specular};
    info.params = {
        {"probes", ParamType::Int, 256, 8, 16384,
         "the most probes of the grid, in cells as near to cubes as whole counts allow over the scene's bounds "
         "(at least 2 along each side)"},
        {"raysPerProbe", ParamType::Int, 256, 1, 1024,
         "rays per probe and frame blended into the atlases (spherical Fibonacci under a random rotation)"},
        {"fixedRays", ParamType::Int, 32, 4, 256,
         "fixed rays per probe and frame for relocation and classification (not blended)"},
        {"hysteresis", ParamType::Float, 0.97, 0.0, 1.0,
         "the share of a probe texel's last value kept at each update (the paper: 0.97)"},
        {"fastTransitions", ParamType::Bool, 1, 0, 1,
         "a texel whose new estimate changed by over 25% (80%) keeps 0.15 less of its last value (none of it), "
         "so that new light settles in a few frames (2021; 0: the plain hysteresis)"},
        {"bounces", ParamType::Bool, 1, 0, 1,
         "ray hits reflect the probes' last irradiance (infinite bounces over frames; 0: one bounce)"},
        {"relocation", ParamType::Bool, 1, 0, 1, "move probes out of solids and away from near surfaces (2021)"},
        {"classification", ParamType::Bool, 1, 0, 1,
         "probes with no surface in their cells, or inside a solid, are inactive: skipped and weightless (2021)"},
        {"bias", ParamType::Float, 0.3, 0.0, 2.0,
         "the self-shadow bias along the normal and the view, per 0.75 of the smallest probe spacing (the "
         "paper: 0.3)"},
    };
    // Every pass with a small grid and few rays.
    info.quickSets = {"probes=27", "raysPerProbe=32", "fixedRays=8"};
    info.create = [](Frame& frame, const ParamValues& v) -> std::unique_ptr<Technique> {
        ProbeFieldSettings s;
        s.probes = v.getInt("probes");
        s.raysPerProbe = v.getInt("raysPerProbe");
        s.fixedRays = v.getInt("fixedRays");
        s.hysteresis = float(v.get("hysteresis"));
        s.fastTransitions = v.getBool("fastTransitions");
        s.bounces = v.getBool("bounces");
        s.relocation = v.getBool("relocation");
        s.classification = v.getBool("classification");
        s.selfShadowBias = float(v.get("bias"));
        return std::make_unique<Ddgi>(frame, s);
    };
    return info;
}

} // namespace bounce::gl
