// Bytes held by each live GL resource, by label: the "bytes allocated per GL resource" of the run's
// JSON record (DESIGN.md, "Model only what a scene needs"). Wrappers register on allocation and
// unregister on destruction, so the table always shows what is alive now.
#pragma once

#include <cstddef>
#include <map>
#include <string>

namespace bounce::gl {

class Allocations {
public:
    static Allocations& instance();
    // Returns a ticket to pass to release().
    int add(const std::string& label, std::size_t bytes);
    void release(int ticket);
    // Live bytes summed by label.
    std::map<std::string, std::size_t> byLabel() const;
    std::size_t totalBytes() const;

private:
    struct Entry {
        std::string label;
        std::size_t bytes;
    };
    std::map<int, Entry> entries_;
    int next_ = 1;
};

// Registers bytes under a label for as long as it lives; move-only.
class AllocationTicket {
public:
    AllocationTicket() = default;
    AllocationTicket(const std::string& label, std::size_t bytes) : ticket_(Allocations::instance().add(label, bytes))
    {}
    ~AllocationTicket()
    {
        if (ticket_) Allocations::instance().release(ticket_);
    }
    AllocationTicket(AllocationTicket&& o) noexcept : ticket_(o.ticket_) { o.ticket_ = 0; }
    AllocationTicket& operator=(AllocationTicket&& o) noexcept
    {
        if (this != &o) {
            if (ticket_) Allocations::instance().release(ticket_);
            ticket_ = o.ticket_;
            o.ticket_ = 0;
        }
        return *this;
    }

private:
    int ticket_ = 0;
};

// Storage a wrapper makes without data is undefined in GL: llvmpipe gives zeros, a GPU driver whatever
// the memory held. With poisoning on (setPoisonNewStorage, or BOUNCE_POISON_STORAGE=1 in the environment)
// buffers are filled with 0xff bytes (NaN as a float, 0xffffffff as a uint) and textures with NaN (float
// formats), 1 (normalised), all ones (integer) or 0.5 (depth), so that reading what no pass wrote shows
// on a software rasteriser too.
bool poisonNewStorage();
void setPoisonNewStorage(bool on);

} // namespace bounce::gl
