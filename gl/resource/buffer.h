// A GL buffer object (DSA), labelled and counted in Allocations.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "gl/resource/allocations.h"
#include "gl/resource/handle.h"

namespace bounce::gl {

struct BufferDeleter {
    void operator()(unsigned id) const;
};

class Buffer {
public:
    Buffer() = default;
    // Immutable storage (glNamedBufferStorage) with GL_DYNAMIC_STORAGE_BIT so update() works; without
    // data it is undefined, or poisoned (allocations.h: poisonNewStorage).
    Buffer(const std::string& label, std::size_t bytes, const void* data = nullptr);
    template <class T>
    static Buffer fromVector(const std::string& label, const std::vector<T>& v)
    {
        return Buffer(label, v.size() * sizeof(T), v.empty() ? nullptr : v.data());
    }

    // v into b: rewritten in place where b already has v's size (uploads made every frame whose size
    // rarely changes, such as still frames' lights), else b is made anew under `label`. True when b was
    // made anew, so that views of it (buffer textures) must be made anew too.
    template <class T>
    static bool assign(Buffer& b, const std::string& label, const std::vector<T>& v)
    {
        const std::size_t bytes = v.size() * sizeof(T);
        if (b && b.bytes() == bytes) {
            if (bytes > 0) b.update(0, bytes, v.data());
            return false;
        }
        b = fromVector(label, v);
        return true;
    }

    unsigned id() const { return handle_.id(); }
    std::size_t bytes() const { return bytes_; }
    explicit operator bool() const { return bool(handle_); }

    void update(std::size_t offset, std::size_t bytes, const void* data);
    void download(std::size_t offset, std::size_t bytes, void* out) const;
    template <class T>
    std::vector<T> download() const
    {
        std::vector<T> v(bytes_ / sizeof(T));
        download(0, v.size() * sizeof(T), v.data());
        return v;
    }
    void clearToZero();
    // glBindBufferBase(target, index) (GL_UNIFORM_BUFFER...); for GL_SHADER_STORAGE_BUFFER `index` is a storage
    // name (SSBO_*), which each program that reads it binds to its own point (gl/resource/storage_bindings.h).
    void bindBase(unsigned target, unsigned index) const;

private:
    Handle<BufferDeleter> handle_;
    std::size_t bytes_ = 0;
    AllocationTicket ticket_;
};

} // namespace bounce::gl
