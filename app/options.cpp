#include "app/options.h"

#include <cmath>
#include <cstdio>

namespace bounce::app {

Options::Options(const Args& args, const std::vector<OptionSpec>& specs, const std::string& usage) : usage_(usage)
{
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--help" || a == "-h") {
            help_ = true;
            continue;
        }
        if (a.rfind("--", 0) != 0 || a.size() == 2) {
            positional_.push_back(a);
            continue;
        }
        std::string name = a.substr(2), value;
        bool inlineValue = false;
        if (const auto eq = name.find('='); eq != std::string::npos) {
            value = name.substr(eq + 1);
            name = name.substr(0, eq);
            inlineValue = true;
        }
        const OptionSpec* spec = nullptr;
        for (const OptionSpec& s : specs)
            if (s.name == name) spec = &s;
        if (!spec) throw UsageError("unknown option '--" + name + "'\n\n" + usage_);
        if (spec->takesValue && !inlineValue) {
            if (i + 1 >= args.size()) throw UsageError("option '--" + name + "' needs a value\n\n" + usage_);
            value = args[++i];
        }
        if (!spec->takesValue && inlineValue) throw UsageError("option '--" + name + "' takes no value");
        if (!spec->repeatable && has(name)) throw UsageError("option '--" + name + "' given twice");
        values_.emplace_back(name, value);
    }
}

bool Options::has(const std::string& name) const
{
    for (const auto& [n, v] : values_)
        if (n == name) return true;
    return false;
}

std::string Options::get(const std::string& name, const std::string& fallback) const
{
    for (const auto& [n, v] : values_)
        if (n == name) return v;
    return fallback;
}

std::vector<std::string> Options::all(const std::string& name) const
{
    std::vector<std::string> out;
    for (const auto& [n, v] : values_)
        if (n == name) out.push_back(v);
    return out;
}

int Options::getInt(const std::string& name, int fallback, int min, int max) const
{
    if (!has(name)) return fallback;
    const double v = getDouble(name, fallback, min, max);
    if (v != std::floor(v)) throw UsageError("--" + name + " needs an integer, not '" + get(name) + "'");
    return int(v);
}

double Options::getDouble(const std::string& name, double fallback, double min, double max) const
{
    if (!has(name)) return fallback;
    const std::string text = get(name);
    std::size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(text, &used);
    } catch (...) {
        used = 0;
    }
    if (used != text.size() || text.empty() || !std::isfinite(v))
        throw UsageError("--" + name + " needs a number, not '" + text + "'");
    if (v < min || v > max) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "--%s must be in [%g, %g], not %s", name.c_str(), min, max, text.c_str());
        throw UsageError(buf);
    }
    return v;
}

void parseSize(const std::string& text, int& width, int& height)
{
    const auto x = text.find('x');
    bool ok = x != std::string::npos && x > 0 && x + 1 < text.size();
    long w = 0, h = 0;
    if (ok) {
        for (std::size_t i = 0; i < text.size(); ++i)
            if (i != x && (text[i] < '0' || text[i] > '9')) ok = false;
        if (ok && x <= 6 && text.size() - x - 1 <= 6) {
            w = std::stol(text.substr(0, x));
            h = std::stol(text.substr(x + 1));
        } else {
            ok = false;
        }
    }
    if (!ok || w < 1 || h < 1 || w > 16384 || h > 16384)
        throw UsageError("--size needs WIDTHxHEIGHT with each in 1..16384 (e.g. 512x512), not '" + text + "'");
    width = int(w);
    height = int(h);
}

} // namespace bounce::app
