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
#include "gl/resource/timer.h"

namespace bounce::gl {

// Choice: one of a list of names (`kbuffer=stencil|atomic|peel`), held as the index into `choices`.
enum class ParamType { Int, Float, Bool, Choice };

// How a changed value reaches a running technique: Rebuild makes the technique anew (buffers, shaders);
// Uniform hands it to Technique::setUniforms() (a shader uniform: the demo's sliders never recompile).
enum class ParamUpdate { Rebuild, Uniform };

// The value an Int or Float parameter holds when it was set to "auto" (allowAuto): the technique chooses.
inline constexpr double kAutoValue = -1e300;

struct ParamDecl {
    std::string name; // "vpls", "depthThreshold"...
    ParamType type = ParamType::Float;
    double defaultValue = 0.0; // Choice: the index of the default choice; kAutoValue: "auto"
    double min = 0.0;
    double max = 0.0;
    std::string meaning;     // one line
    bool powerOfTwo = false; // Int only: the value must also be a power of two
    ParamUpdate update = ParamUpdate::Rebuild;
    std::vector<std::string> choices{}; // Choice only: the names, in index order
    bool allowAuto = false;             // Int/Float: "auto" is accepted too (instead of a sentinel number such as -1)

    std::string typeName() const;
    // The value as a user writes it: "auto", a choice's name, "on"/"off", or the number.
    std::string text(double value) const;
    nlohmann::json toJson() const; // every field, for `bounce list --json`
};

// A Choice parameter's declaration.
ParamDecl choiceParam(std::string name, std::vector<std::string> choices, int defaultIndex, std::string meaning,
                      ParamUpdate update = ParamUpdate::Rebuild);

// Parameter values by name, every declared parameter present (defaults filled in).
class ParamValues {
public:
    ParamValues() = default;
    explicit ParamValues(const std::vector<ParamDecl>& decls);
    double get(const std::string& name) const;
    int getInt(const std::string& name) const { return int(get(name)); }
    bool getBool(const std::string& name) const { return get(name) != 0.0; }
    bool isAuto(const std::string& name) const { return get(name) == kAutoValue; }
    // A Choice parameter's name (the declarations say which names there are).
    const std::string& getChoice(const std::vector<ParamDecl>& decls, const std::string& name) const;
    // Checks the name is declared, parses by type and checks the range; throws std::invalid_argument
    // saying what is allowed.
    void set(const std::vector<ParamDecl>& decls, const std::string& name, const std::string& text);
    const std::map<std::string, double>& values() const { return values_; }
    void setValue(const std::string& name, double v) { values_[name] = v; }
    // Name -> value as the user writes it ("auto", choice names, numbers), for records and scripts.
    nlohmann::json toJson(const std::vector<ParamDecl>& decls) const;
    // The names whose values differ from `other`'s.
    std::vector<std::string> changed(const ParamValues& other) const;

private:
    std::map<std::string, double> values_;
};

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
