// The directions of the global ray-bundles (Hermes et al. 2010, Sec. 4.3) and the orthographic view of
// each (Sec. 3, Fig. 4). No GL here.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace bounce::gl {

// Sec. 4.3: the Halton sequence (bases 2 and 3) on the unit sphere, uniform in area; both orientations
// of a direction are used, so each receiver gets one sample of its hemisphere per direction (density
// 1 / (2 pi) there, Eq. 2). Direction `index` is the sequence's point bundleSequenceIndex(index) + 1
// (point 0 is the pole), drawn from the frame sampler's stream BundleDirection (gl/frame/frame_sampler.h).
glm::vec3 bundleDirection(std::uint64_t index);

// The order in which the bundles take the Halton points: shuffled within blocks of kBundleShuffleBlock.
// The glossy transfer (Sec. 5.4) pairs direction i with direction i + 1 (light arriving along one leaves
// along the next) and interleaving (Sec. 5.5) sends along i + 1 what arrived along i; both need
// consecutive directions independent, as the paper's "uniformly distributed random directions" are.
// Consecutive Halton points are not: base 2's radical inverse of an even index plus one is that of the
// index plus 1/2, so every second pair has cos(theta) exactly 1 apart and light arriving from above a
// horizontal glossy face never left it upwards (cornell-glossy: the lamp's reflection off the tall
// block's top missing from the ceiling and the back wall). Each complete block is the same set of points
// as the unshuffled sequence's, so a multiple of the block is as well stratified.
inline constexpr std::uint32_t kBundleShuffleBlock = 64;
std::uint64_t bundleSequenceIndex(std::uint64_t index);
// A sub-pixel offset of the k-buffer's grid for direction `index` (Halton bases 5 and 7), in [0, 1)^2
// pixels: the rays of successive directions do not all pass through the same lattice.
glm::vec2 bundleJitter(std::uint64_t index);

struct BundleView {
    glm::vec3 dir{0.0f, 0.0f, 1.0f}, right{1.0f, 0.0f, 0.0f}, up{0.0f, 1.0f, 0.0f};
    glm::vec3 centre{0.0f};
    float radius = 1.0f;
    glm::vec2 jitter{0.0f};
    int size = 1;
    // World to clip: x, y over the sphere's disk (plus the jitter), z = depth along dir over [-r, r].
    glm::mat4 viewProj{1.0f};
};

// The bounding sphere of the scene (the bounds' centre, half their diagonal, 1% larger so that nothing
// lies on its surface) looked at along `dir` by a size x size k-buffer.
BundleView bundleView(const core::Bounds& bounds, glm::vec3 dir, glm::vec2 jitter, int size);

} // namespace bounce::gl
