// FNV-1a, 64 bits: a hash that is the same on every machine, compiler and run (std::hash is none of these),
// for cache keys, cache file names and ids. Bytes fed in pieces hash as the same bytes fed at once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>

namespace bounce::core {

class Fnv1a {
public:
    // The published offset basis (0xcbf29ce484222325): the published test vectors hold with it.
    static constexpr std::uint64_t kOffsetBasis = 14695981039346656037ull;
    // The basis that the scene content hash, the reference cache keys and checksums and the roofline probe
    // file names have always used: the published one with its last decimal digit missing. Those values are
    // stored on disk under these names (existing cache entries), so they keep it.
    static constexpr std::uint64_t kLegacyBasis = 1469598103934665603ull;
    static constexpr std::uint64_t kPrime = 1099511628211ull;

    constexpr explicit Fnv1a(std::uint64_t basis = kOffsetBasis) : h_(basis) {}

    Fnv1a& add(const void* data, std::size_t size)
    {
        const auto* c = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) h_ = (h_ ^ c[i]) * kPrime;
        return *this;
    }
    Fnv1a& add(std::string_view text) { return add(text.data(), text.size()); }
    // The bytes of a plain value (numbers, enums, glm vectors): the same value on the same platform.
    template <class T>
    Fnv1a& addBytesOf(const T& value)
    {
        static_assert(std::is_trivially_copyable_v<T>, "hash the members, not the object");
        return add(&value, sizeof value);
    }

    constexpr std::uint64_t value() const { return h_; }
    // 16 lowercase hex digits, zero-padded.
    std::string hex() const
    {
        std::string s(16, '0');
        for (int i = 0; i < 16; ++i) s[i] = "0123456789abcdef"[(h_ >> (60 - 4 * i)) & 0xf];
        return s;
    }

private:
    std::uint64_t h_;
};

} // namespace bounce::core
