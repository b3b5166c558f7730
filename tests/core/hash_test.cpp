// core::Fnv1a (core/hash.h): the published FNV-1a 64 test vectors, pieces hash as the whole, and the legacy
// basis that the scene hash and the reference cache keys keep.
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "core/hash.h"

namespace {

using bounce::core::Fnv1a;

TEST(Hash, PublishedTestVectors)
{
    EXPECT_EQ(Fnv1a().value(), 0xcbf29ce484222325ull);
    EXPECT_EQ(Fnv1a().hex(), "cbf29ce484222325");
    EXPECT_EQ(Fnv1a().add("a").hex(), "af63dc4c8601ec8c");
    EXPECT_EQ(Fnv1a().add("foobar").hex(), "85944171f73967e8");
    EXPECT_EQ(Fnv1a().add("foobar").value(), 0x85944171f73967e8ull);
}

TEST(Hash, PiecesHashAsTheWhole)
{
    const std::string text = "the quick brown fox jumps over the lazy dog";
    const std::uint64_t whole = Fnv1a().add(text).value();
    for (std::size_t cut = 0; cut <= text.size(); ++cut) {
        Fnv1a f;
        f.add(text.data(), cut).add(std::string_view(text).substr(cut));
        EXPECT_EQ(f.value(), whole) << "cut at " << cut;
    }
    Fnv1a bytes;
    for (char c : text) bytes.addBytesOf(c);
    EXPECT_EQ(bytes.value(), whole);
    EXPECT_EQ(Fnv1a().add("foo").add("").add("bar").hex(), "85944171f73967e8");
}

TEST(Hash, HexIsSixteenDigits)
{
    EXPECT_EQ(Fnv1a(0).hex(), "0000000000000000");
    EXPECT_EQ(Fnv1a(0x0123456789abcdefull).hex(), "0123456789abcdef");
    EXPECT_EQ(Fnv1a(~0ull).hex(), "ffffffffffffffff");
}

// The basis the scene hash, the reference cache and the roofline probe files were written with: not the
// published one, and it must stay as it is (their values are names of files on disk).
TEST(Hash, LegacyBasisKeepsItsValues)
{
    EXPECT_EQ(Fnv1a(Fnv1a::kLegacyBasis).value(), 1469598103934665603ull);
    EXPECT_NE(Fnv1a::kLegacyBasis, Fnv1a::kOffsetBasis);
    std::uint64_t h = 1469598103934665603ull; // the loop as it was written in scene.cpp and reference.cpp
    for (unsigned char c : std::string("foobar")) h = (h ^ c) * 1099511628211ull;
    EXPECT_EQ(Fnv1a(Fnv1a::kLegacyBasis).add("foobar").value(), h);
}

} // namespace
