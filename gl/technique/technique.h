// The Technique interface (DESIGN.md): a technique declares its name, the light paths it computes, its
// parameters (name, type, default, range, meaning) and its passes; it receives the frame and writes
// linear indirect radiance into frame.indirect(). The CLI, the demo, the benchmark and the tests drive
// techniques only through this interface and the registry below.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/light_paths.h"
#include "gl/frame/frame.h"
#include "gl/frame/params.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

struct Counter {
    std::string name; // "vpls", "fragments.level0"...
    double value = 0.0;
};

class Technique {
public:
    virtual ~Technique() = default;
    // Runs after the frame's shadow/G-buffer/direct passes; writes frame.indirect() (already cleared).
    virtual void render(Frame& frame, PassTimers& timers) = 0;
    // Counts of the last frame (VPLs, fragments per level...).
    virtual std::vector<Counter> counters() const { return {}; }
    // New values of parameters declared ParamUpdate::Uniform (the others are unchanged): take them
    // without rebuilding. A technique that declares a uniform parameter must override this.
    virtual void setUniforms(const ParamValues& /*values*/) {}
    // Progressive techniques (TechniqueInfo::progressive): drop what has accumulated and start over.
    // They also start over by themselves when Frame::version() changes.
    virtual void restart() {}
    // Progressive techniques: accumulation steps since the last start (ray-bundle directions, ...).
    virtual int accumulatedSteps() const { return 0; }
    // What the run's JSON record should say beyond numbers (which capture ran and why...); {} for nothing.
    virtual nlohmann::json notes() const { return {}; }
    // True when the technique writes the light that emitting triangles reflect into frame.indirect()
    // itself (grb's emitters=bundles, Sec. 5.1): the frame's direct pass then leaves it out
    // (Frame::setAreaLightsInDirect), so that it is not counted twice.
    virtual bool carriesEmittersLight() const { return false; }
    // With carriesEmittersLight(): whether the technique reads the emitting meshes' shadow cubes (the frame
    // renders them only then).
    virtual bool readsAreaShadowMaps() const { return true; }
    // Whether any of the technique's passes reads the frame's shadow maps (a point cloud's light, a ray hit's
    // direct light in the moving form, ...). False lets the frame skip its shadow pass in the frames whose
    // own direct pass reads none either (Frame::setShadowMapsRead). Asked before every frame's shadow pass,
    // of the frame's lights as they are then. True unless a technique says otherwise.
    virtual bool readsShadowMaps(const Frame& /*frame*/) const { return true; }
    // False when the technique's work at the camera's pixels is a lookup of what it built apart from the
    // camera (grb's display of its atlases without the final glossy bounce): a coarser indirect resolution
    // (Renderer::setIndirectScale) would save next to nothing and lose detail, and the Renderer then draws
    // its indirect light at full resolution at every scale.
    virtual bool indirectScales() const { return true; }
};

// The G-buffer channels a technique may read (Frame::bindGBuffer, glsl/common/gbuffer.glsl).
enum class GBufferChannel { Position, Normal, Diffuse, Specular, Emission, Depth, Direct };
std::string gbufferChannelName(GBufferChannel c);

// A pass a technique times (PassTimers::scope(name)). `when` is empty for a pass every frame runs with
// the default parameters, else the condition under which it runs, in words.
struct PassDecl {
    std::string name;
    std::string meaning; // one line
    std::string when;
};

struct TechniqueInfo {
    std::string name;
    std::string paper;                                      // "Nichols, Shopf & Wyman 2009" or "-"
    core::LightPaths lightPaths = core::LightPaths::Direct; // the reference it claims
    std::string summary;                                    // one line
    std::vector<ParamDecl> params;
    std::vector<PassDecl> passes;      // every pass it times, beyond the frame's own (framePasses())
    std::vector<GBufferChannel> reads; // the G-buffer channels its shaders read
    // Accumulates over frames (ray-bundle directions, progressive point projection): `--frames N` is N
    // accumulation steps, and it starts over when Frame::version() changes.
    bool progressive = false;
    // Its indirect light goes through the frame's temporal reuse when the frame parameter `temporal` is on
    // (gl/renderer.h): a technique that draws its samples anew each frame. A progressive one averages its
    // own steps and does not; nor does one without indirect light.
    bool temporalReuse = false;
    // "key=value" settings that make the technique cheap while still running every pass its defaults run
    // (fewer photons, directions, rays, smaller buffers): the conformance and determinism tests render
    // with them, so that each new technique costs the suite seconds, not minutes, on a CPU rasteriser.
    std::vector<std::string> quickSets;
    std::function<std::unique_ptr<Technique>(Frame&, const ParamValues&)> create;

    nlohmann::json toJson() const; // everything but `create`, for `bounce list --json`
};

// Every registered technique, in a fixed order. Families add themselves in registry.cpp.
const std::vector<TechniqueInfo>& techniques();
// Throws std::invalid_argument listing the known names.
const TechniqueInfo& findTechnique(const std::string& name);

// The passes the frame itself times around every technique: shadow, gbuffer, direct, composite.
const std::vector<PassDecl>& framePasses();

// Frame parameters (shadow map size, PCF...) that every technique shares; --set accepts them too.
const std::vector<ParamDecl>& frameParams();
FrameSettings frameSettingsFrom(const ParamValues& frameValues, int width, int height);

} // namespace bounce::gl
