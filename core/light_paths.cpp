#include "core/light_paths.h"

#include <stdexcept>

namespace bounce::core {

namespace {

struct NamedPaths {
    const char* name;
    LightPaths paths;
};

constexpr NamedPaths kPathNames[] = {
    {"direct", LightPaths::Direct},
    {"onebounce", LightPaths::OneBounce},
    {"onebounce-novis", LightPaths::OneBounceNoVis},
    {"onebounce-indirect", LightPaths::OneBounceIndirect},
    {"onebounce-novis-indirect", LightPaths::OneBounceNoVisIndirect},
    {"full", LightPaths::Full},
};

} // namespace

LightPaths parseLightPaths(const std::string& name)
{
    for (const NamedPaths& p : kPathNames)
        if (name == p.name) return p.paths;
    std::string allowed;
    for (const NamedPaths& p : kPathNames) allowed += std::string(allowed.empty() ? "" : ", ") + p.name;
    throw std::invalid_argument("unknown light paths '" + name + "' (allowed: " + allowed + ")");
}

std::string lightPathsName(LightPaths paths)
{
    for (const NamedPaths& p : kPathNames)
        if (paths == p.paths) return p.name;
    return "unknown";
}

std::vector<std::string> lightPathsNames()
{
    std::vector<std::string> names;
    for (const NamedPaths& p : kPathNames) names.emplace_back(p.name);
    return names;
}

int indirectBounces(LightPaths paths)
{
    switch (paths) {
    case LightPaths::Direct: return 0;
    case LightPaths::Full: return -1;
    default: return 1;
    }
}

} // namespace bounce::core
