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

#include "gl/frame/frame.h"
#include "gl/resource/timer.h"

namespace bounce::gl {

enum class ParamType { Int, Float, Bool };

struct ParamDecl {
    std::string name;       // "vpls", "depthThreshold"...
    ParamType type = ParamType::Float;
    double defaultValue = 0.0;
    double min = 0.0;
    double max = 0.0;
    std::string meaning;    // one line
    bool powerOfTwo = false; // Int only: the value must also be a power of two
};

// Parameter values by name, every declared parameter present (defaults filled in).
class ParamValues {
public:
    ParamValues() = default;
    explicit ParamValues(const std::vector<ParamDecl>& decls);
    double get(const std::string& name) const;
    int getInt(const std::string& name) const { return int(get(name)); }
    bool getBool(const std::string& name) const { return get(name) != 0.0; }
    // Checks the name is declared, parses by type and checks the range; throws std::invalid_argument
    // saying what is allowed.
    void set(const std::vector<ParamDecl>& decls, const std::string& name, const std::string& text);
    const std::map<std::string, double>& values() const { return values_; }
    void setValue(const std::string& name, double v) { values_[name] = v; }

private:
    std::map<std::string, double> values_;
};

struct Counter {
    std::string name;   // "vpls", "fragments.level0"...
    double value = 0.0;
};

class Technique {
public:
    virtual ~Technique() = default;
    // Runs after the frame's shadow/G-buffer/direct passes; writes frame.indirect() (already cleared).
    virtual void render(Frame& frame, PassTimers& timers) = 0;
    // Counts of the last frame (VPLs, fragments per level...).
    virtual std::vector<Counter> counters() const { return {}; }
};

struct TechniqueInfo {
    std::string name;
    std::string paper;       // "Nichols, Shopf & Wyman 2009" or "-"
    std::string lightPaths;  // the reference it claims: "direct", "onebounce-novis", "onebounce", "full"
    std::string summary;     // one line
    std::vector<ParamDecl> params;
    std::function<std::unique_ptr<Technique>(Frame&, const ParamValues&)> create;
};

// Every registered technique, in a fixed order. Families add themselves in registry.cpp.
const std::vector<TechniqueInfo>& techniques();
// Throws std::invalid_argument listing the known names.
const TechniqueInfo& findTechnique(const std::string& name);

// Frame parameters (shadow map size, PCF...) that every technique shares; --set accepts them too.
const std::vector<ParamDecl>& frameParams();
FrameSettings frameSettingsFrom(const ParamValues& frameValues, int width, int height);

} // namespace bounce::gl
