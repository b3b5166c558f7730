#include "gl/technique/technique.h"

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

namespace {
std::string describe(const ParamDecl& d)
{
    std::ostringstream s;
    const char* type = d.type == ParamType::Int ? "int" : d.type == ParamType::Bool ? "bool" : "float";
    s << d.name << " (" << type;
    if (d.type != ParamType::Bool) s << " in [" << d.min << ", " << d.max << "]";
    if (d.powerOfTwo) s << ", a power of two";
    s << ", default " << d.defaultValue << ")";
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
        throw std::invalid_argument("unknown parameter '" + name + "'; allowed:" + (allowed.empty() ? " none" : allowed));
    }
    double v = 0.0;
    if (decl->type == ParamType::Bool) {
        if (text == "1" || text == "true" || text == "on") v = 1.0;
        else if (text == "0" || text == "false" || text == "off") v = 0.0;
        else throw std::invalid_argument("parameter '" + name + "' is a bool: give 0/1, true/false or on/off, not '" + text + "'");
    } else {
        std::size_t used = 0;
        try { v = std::stod(text, &used); } catch (...) { used = 0; }
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

const TechniqueInfo& findTechnique(const std::string& name)
{
    for (const TechniqueInfo& t : techniques())
        if (t.name == name) return t;
    std::string known;
    for (const TechniqueInfo& t : techniques()) known += (known.empty() ? "" : ", ") + t.name;
    throw std::invalid_argument("unknown technique '" + name + "'; known: " + known);
}

const std::vector<ParamDecl>& frameParams()
{
    static const std::vector<ParamDecl> p = {
        {"shadow.size", ParamType::Int, 1024, 16, 8192, "shadow-map resolution per view (texels per side)"},
        {"shadow.pcf", ParamType::Int, 1, 0, 4, "PCF kernel radius in texels (0: one tap)"},
        {"shadow.linear", ParamType::Bool, 1, 0, 1, "hardware bilinear depth comparison (off: hard shadow edges)"},
        {"textures.size", ParamType::Int, 512, 1, 4096, "base-colour textures are resampled to this size"},
    };
    return p;
}

FrameSettings frameSettingsFrom(const ParamValues& v, int width, int height)
{
    FrameSettings s;
    s.width = width;
    s.height = height;
    s.shadowMapSize = v.getInt("shadow.size");
    s.pcfRadius = v.getInt("shadow.pcf");
    s.pcfLinear = v.getBool("shadow.linear");
    s.textureSize = v.getInt("textures.size");
    return s;
}

} // namespace bounce::gl
