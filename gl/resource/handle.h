// A move-only owner of one GL object name, with the function that deletes it. The building block of
// the RAII wrappers in gl/resource/: no raw glGen* / glCreate* outside this folder.
#pragma once

#include <utility>

namespace bounce::gl {

template <class Deleter>
class Handle {
public:
    Handle() = default;
    explicit Handle(unsigned id) : id_(id) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, 0u)) {}
    Handle& operator=(Handle&& o) noexcept
    {
        if (this != &o) {
            reset();
            id_ = std::exchange(o.id_, 0u);
        }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;

    unsigned id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    void reset()
    {
        if (id_) Deleter{}(id_);
        id_ = 0;
    }

private:
    unsigned id_ = 0;
};

} // namespace bounce::gl
