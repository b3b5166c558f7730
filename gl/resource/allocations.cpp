#include "gl/resource/allocations.h"

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

} // namespace bounce::gl
