// The radiance atlases of global ray-bundles (Hermes et al. 2010, Sec. 4.1 and 5; what each holds:
// glsl/technique/grb/radiance.glsl): the seed of punctual direct light, the sender/receiver pairs of
// the direct and indirect sums that swap after every direction (Sec. 5.5), and, only when the scene has
// glossy materials, the pair of glossy transfer atlases (Sec. 5.4).
#pragma once

#include <cstdint>

#include <vector>

#include "gl/frame/frame.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"
#include "gl/technique/grb/bundle_directions.h"
#include "gl/technique/grb/grb_atlas.h"
#include "gl/technique/grb/kbuffer.h"

namespace bounce::gl {

struct RadianceSettings {
    bool glossy = false;   // the scene has a glossy lobe somewhere: allocate the transfer atlases
    bool punctual = false; // the scene has point, spot or directional lights: seed them
    // The scene has emitting triangles and a glossy lobe: the glossy transfer takes the emitters' light by
    // sampling them (as the frame's still frames do) instead of through the bundles.
    bool areaGlossy = false;
    bool interleaved = true; // Sec. 5.5; false: senders send only the seed and their emission (one bounce)
};

class RadianceAtlases {
public:
    RadianceAtlases(const GrbAtlas& atlas, const KBuffer& kbuffer, const RadianceSettings& settings);

    // Zero sums: the accumulation starts over.
    void clear();
    // The punctual lights' direct light into the seed atlas (pass "seed"), through the frame's shadow maps.
    void seed(const Frame& frame, const GrbAtlas& atlas, PassTimers& timers);
    // Eq. 3 for one direction over every atlas texel (pass "transfer"), then the pair swaps. `next` is
    // the following direction, for which the glossy transfer atlas is prepared.
    void transfer(const Frame& frame, const GrbAtlas& atlas, const KBuffer& kbuffer, const BundleView& view,
                  const glm::vec3& next, PassTimers& timers);
    // The seed and the current sender atlases at their units (radiance.glsl).
    void bindSender() const;
    // radiance.glsl's senderRadiance for one sender texel, counted (part of the PassCost of "transfer" and
    // "final-glossy", which look up at most one sender per receiver).
    PassCost senderRadianceCost() const;
    std::vector<Define> defines() const;

    const Texture& seedAtlas() const { return seed_; }
    const Texture& direct() const { return direct_[current_]; }
    const Texture& indirect() const { return indirect_[current_]; }
    const Texture& glossy() const { return glossy_[current_]; }
    const RadianceSettings& settings() const { return settings_; }

private:
    RadianceSettings settings_;
    int width_, height_;
    Texture seed_, direct_[2], indirect_[2], glossy_[2];
    Framebuffer fbo_[2], seedFbo_;
    Program transfer_, seedProgram_;
    VertexArray vao_;
    int current_ = 0;             // the sender pair; the transfer writes the other
    std::uint64_t transfers_ = 0; // directions transferred since the atlases were made (AREA_GLOSSY's rotation)
};

} // namespace bounce::gl
