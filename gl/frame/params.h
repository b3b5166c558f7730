// Parameters by name (`--set name=value`, the demo's sliders, bench configs): their declarations (type,
// default, range, meaning) and the values a run holds. The frame's services declare theirs here
// (rsmParams, multiresParams) as the techniques do (gl/technique/technique.h).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

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

} // namespace bounce::gl
