#include "gl/frame/params.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace bounce::gl {

ParamValues::ParamValues(const std::vector<ParamDecl>& decls)
{
    for (const ParamDecl& d : decls) values_[d.name] = d.defaultValue;
}

double ParamValues::get(const std::string& name) const
{
    const auto it = values_.find(name);
    if (it == values_.end()) throw std::invalid_argument("no parameter '" + name + "'");
    return it->second;
}

std::string ParamDecl::typeName() const
{
    switch (type) {
    case ParamType::Int: return "int";
    case ParamType::Bool: return "bool";
    case ParamType::Choice: return "choice";
    default: return "float";
    }
}

std::string ParamDecl::text(double value) const
{
    if (allowAuto && value == kAutoValue) return "auto";
    if (type == ParamType::Bool) return value != 0.0 ? "on" : "off";
    if (type == ParamType::Choice) {
        const auto i = std::size_t(value);
        return value >= 0.0 && i < choices.size() ? choices[i] : "?";
    }
    std::ostringstream s;
    s << value;
    return s.str();
}

nlohmann::json ParamDecl::toJson() const
{
    nlohmann::json j = {{"name", name},
                        {"type", typeName()},
                        {"default", text(defaultValue)},
                        {"meaning", meaning},
                        {"update", update == ParamUpdate::Uniform ? "uniform" : "rebuild"}};
    if ((type == ParamType::Int || type == ParamType::Float) && defaultValue != kAutoValue) j["default"] = defaultValue;
    if (type == ParamType::Int || type == ParamType::Float) {
        j["min"] = min;
        j["max"] = max;
        if (powerOfTwo) j["powerOfTwo"] = true;
        if (allowAuto) j["allowAuto"] = true;
    }
    if (type == ParamType::Choice) j["choices"] = choices;
    return j;
}

ParamDecl choiceParam(std::string name, std::vector<std::string> choices, int defaultIndex, std::string meaning,
                      ParamUpdate update)
{
    ParamDecl d;
    d.name = std::move(name);
    d.type = ParamType::Choice;
    d.defaultValue = defaultIndex;
    d.min = 0;
    d.max = double(choices.size()) - 1.0;
    d.meaning = std::move(meaning);
    d.update = update;
    d.choices = std::move(choices);
    return d;
}

const std::string& ParamValues::getChoice(const std::vector<ParamDecl>& decls, const std::string& name) const
{
    const double v = get(name);
    for (const ParamDecl& d : decls)
        if (d.name == name && d.type == ParamType::Choice && v >= 0.0 && std::size_t(v) < d.choices.size())
            return d.choices[std::size_t(v)];
    throw std::invalid_argument("parameter '" + name + "' is not a choice");
}

nlohmann::json ParamValues::toJson(const std::vector<ParamDecl>& decls) const
{
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [name, v] : values_) {
        const ParamDecl* decl = nullptr;
        for (const ParamDecl& d : decls)
            if (d.name == name) decl = &d;
        if (!decl)
            j[name] = v;
        else if (decl->type == ParamType::Choice || (decl->allowAuto && v == kAutoValue))
            j[name] = decl->text(v);
        else if (decl->type == ParamType::Bool)
            j[name] = v != 0.0;
        else
            j[name] = v;
    }
    return j;
}

std::vector<std::string> ParamValues::changed(const ParamValues& other) const
{
    std::vector<std::string> names;
    for (const auto& [name, v] : values_) {
        const auto it = other.values_.find(name);
        if (it == other.values_.end() || it->second != v) names.push_back(name);
    }
    for (const auto& [name, v] : other.values_)
        if (!values_.count(name)) names.push_back(name);
    return names;
}

namespace {
std::string describe(const ParamDecl& d)
{
    std::ostringstream s;
    s << d.name << " (" << d.typeName();
    if (d.type == ParamType::Choice) {
        s << ":";
        for (std::size_t i = 0; i < d.choices.size(); ++i) s << (i ? "|" : " ") << d.choices[i];
    } else if (d.type != ParamType::Bool) {
        s << " in [" << d.min << ", " << d.max << "]";
    }
    if (d.allowAuto) s << " or auto";
    if (d.powerOfTwo) s << ", a power of two";
    s << ", default " << d.text(d.defaultValue) << ")";
    return s.str();
}
} // namespace

void ParamValues::set(const std::vector<ParamDecl>& decls, const std::string& name, const std::string& text)
{
    const ParamDecl* decl = nullptr;
    for (const ParamDecl& d : decls)
        if (d.name == name) decl = &d;
    if (!decl) {
        std::string allowed;
        for (const ParamDecl& d : decls) allowed += "\n  " + describe(d);
        throw std::invalid_argument("unknown parameter '" + name +
                                    "'; allowed:" + (allowed.empty() ? " none" : allowed));
    }
    double v = 0.0;
    if (decl->allowAuto && text == "auto") {
        v = kAutoValue;
    } else if (decl->type == ParamType::Choice) {
        const auto it = std::find(decl->choices.begin(), decl->choices.end(), text);
        if (it == decl->choices.end())
            throw std::invalid_argument("parameter " + describe(*decl) + ": '" + text + "' is not one of the choices");
        v = double(it - decl->choices.begin());
    } else if (decl->type == ParamType::Bool) {
        if (text == "1" || text == "true" || text == "on")
            v = 1.0;
        else if (text == "0" || text == "false" || text == "off")
            v = 0.0;
        else
            throw std::invalid_argument("parameter '" + name + "' is a bool: give 0/1, true/false or on/off, not '" +
                                        text + "'");
    } else {
        std::size_t used = 0;
        try {
            v = std::stod(text, &used);
        } catch (...) {
            used = 0;
        }
        if (used != text.size() || text.empty() || !std::isfinite(v))
            throw std::invalid_argument("parameter '" + name + "' needs a number, not '" + text + "'");
        if (decl->type == ParamType::Int && v != std::floor(v))
            throw std::invalid_argument("parameter '" + name + "' is an integer, not '" + text + "'");
        if (v < decl->min || v > decl->max)
            throw std::invalid_argument("parameter " + describe(*decl) + ": " + text + " is out of range");
        if (decl->powerOfTwo && !std::has_single_bit(static_cast<unsigned long long>(v)))
            throw std::invalid_argument("parameter " + describe(*decl) + ": " + text + " is not a power of two");
    }
    values_[name] = v;
}

} // namespace bounce::gl
