// How deeply a JSON text nests arrays and objects, found by one pass over its bytes (no recursion, no
// allocation). tinygltf turns JSON into its own value type recursively, so a glTF nesting ~30,000 levels
// (a 60 KB file) overflows the stack; the loader refuses texts deeper than kMaxGltfJsonDepth first.
#pragma once

#include <cstddef>

namespace bounce::core {

// glTF itself nests about 6 levels; `extras` may add application data, but nothing real comes near this.
inline constexpr std::size_t kMaxGltfJsonDepth = 256;

// The maximum nesting depth of [ and { in [begin, end), skipping strings (with their escapes). Counts
// what it sees: it does not validate the JSON.
std::size_t jsonNestingDepth(const char* begin, const char* end);

} // namespace bounce::core
