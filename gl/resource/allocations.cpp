#include "gl/resource/allocations.h"

#include <cstdlib>

namespace bounce::gl {

Allocations& Allocations::instance()
{
    static Allocations a;
    return a;
}

int Allocations::add(const std::string& label, std::size_t bytes)
{
    const int t = next_++;
    entries_[t] = {label, bytes};
    return t;
}

void Allocations::release(int ticket)
{
    entries_.erase(ticket);
}

std::map<std::string, std::size_t> Allocations::byLabel() const
{
    std::map<std::string, std::size_t> out;
    for (const auto& [t, e] : entries_) out[e.label] += e.bytes;
    return out;
}

std::size_t Allocations::totalBytes() const
{
    std::size_t n = 0;
    for (const auto& [t, e] : entries_) n += e.bytes;
    return n;
}

namespace {
int poisonSetting = -1; // -1: not set yet, read from the environment on first use
}

bool poisonNewStorage()
{
    if (poisonSetting < 0) {
        const char* env = std::getenv("BOUNCE_POISON_STORAGE");
        poisonSetting = env && *env && std::string(env) != "0" ? 1 : 0;
    }
    return poisonSetting == 1;
}

void setPoisonNewStorage(bool on)
{
    poisonSetting = on ? 1 : 0;
}

} // namespace bounce::gl
