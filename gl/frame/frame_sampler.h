// The frame's sampler: one owner for what the frame and the techniques draw from low-discrepancy
// sequences (pbrt's Sampler is the model). It counts frames (frameIndex: every frame, still or moving)
// and still frames (stillIndex: the frames since the view last changed, 0 while it moves), gives each
// still frame's point in the pixel, and hands out the sample streams by name: each stream is its own
// dimensions of Halton's sequence, or its own scrambling of Sobol's, so that no two consumers draw the
// same numbers and correlate (two of grb's streams share the frame's dimensions, declared in the table
// with the reason). A new consumer adds a row to the table (frame_sampler.cpp); the test
// FrameSampler.NoTwoStreamsShareADimension checks the rows, and Layout.SequencesOnlyThroughTheSampler
// that nothing in gl/ draws from core's sequences past it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::gl {

enum class SampleStream {
    PixelJitter,        // the still frame's point in the pixel (the G-buffer's jitter)
    ShadowShift,        // the shadow maps' sub-texel shift in still frames (ShadowMaps)
    AreaLightPoint,     // the still frame's point on each emitting mesh (ShadowMaps::areaSample)
    AreaGlossyRotation, // the rotation of the emitters' points the direct pass's glossy lobes take (Frame)
    BundleDirection,    // a global ray-bundle's direction (grb: bundleDirection)
    BundleJitter,       // a bundle's sub-texel offset (grb: bundleJitter)
    AtlasAreaRotation,  // the emitters' points of an atlas transfer (grb: RadianceAtlases)
    DirectSubsample,    // a frame's further points in the pixel for its direct light (*.directSamples)
};

enum class SampleSequence { Halton, Sobol };

struct SampleStreamInfo {
    SampleStream stream;
    const char* name;
    SampleSequence sequence;
    int firstDimension;  // Halton: the stream's first dimension (it takes two)
    std::uint32_t seed;  // Sobol: the stream's Owen scrambling (core::sobol2)
    const char* drawnBy; // the consumer, for the table and its test
    // A stream whose numbers this one knowingly shares (the same dimensions of Halton's sequence, drawn at
    // other indices), with the reason in the table; nullptr for none. The test accepts only declared pairs.
    const char* shares = nullptr;
};

class FrameSampler {
public:
    // Every stream, in SampleStream's order.
    static const std::vector<SampleStreamInfo>& streams();
    static const SampleStreamInfo& info(SampleStream stream);
    // Point `index` of the stream: two numbers in [0, 1).
    static glm::vec2 sample2(SampleStream stream, std::uint64_t index);

    // A new frame: frameIndex advances; still frames advance stillIndex, a moving one (still false) sets it
    // to 0 and samples the pixel at its centre.
    void advance(bool still);
    std::uint64_t frameIndex() const { return frameIndex_; }
    int stillIndex() const { return stillIndex_; }
    // The index of the frame's own samples: its point in the pixel (still frames only), the shadow maps'
    // shift, the emitters' points. A still frame's is its still index; a moving frame's is 0 (the direct
    // light's moving form: one frame that stands alone), or, with moving samples (the temporal reuse of the
    // direct light, gl/renderer.h), a new index every frame (frameIndex + 1), so that the reuse averages new
    // samples rather than one sample again and again. Moving frames keep their pixels at their centres
    // either way: a jittered frame shown alone moves every edge, and a reuse that restarts at the
    // silhouettes while the camera moves shows them one jittered sample at a time (gl/frame/README.md).
    int sampleIndex() const { return sampleIndex_; }
    // The frame's offset from the pixel's centre, each component in [-0.5, 0.5) (0 in a moving frame).
    glm::vec2 jitter() const { return jitter_; }
    // Frames with `perFrame` > 1 samples of the direct light (Frame::renderDirectSubsamples): the jitter of
    // sample `sample` of this frame, 1 .. perFrame - 1 from the stream DirectSubsample (drawn at
    // (max(sampleIndex, 1) - 1) (perFrame - 1) + sample - 1: still frames and moving frames with moving
    // samples draw new points every frame, other moving frames the same ones), 0 the frame's own
    // (PixelJitter, a moving frame's pixel centre) again, which the technique's G-buffer keeps.
    void setDirectSubsample(int sample, int perFrame);
    // A seed of a shader's hashed random numbers (glsl/common/random.glsl) for this frame: `base` in a moving
    // frame (still frame 0), so that its image stays what it was; base mixed with the still index after, so
    // that each still frame draws new numbers and the still frames' mean converges. With fresh moving seeds
    // (temporal reuse on: gl/renderer.h), a moving frame mixes in the frame index instead, so that the reuse
    // averages new samples rather than one frame's again.
    std::uint32_t hashSeed(std::uint32_t base) const
    {
        if (stillIndex_ > 0) return base ^ (std::uint32_t(stillIndex_) * 0x9E3779B9u);
        return freshMovingSeeds_ ? base ^ (std::uint32_t(frameIndex_) * 0x85EBCA6Bu + 0x27D4EB2Fu) : base;
    }
    void setFreshMovingSeeds(bool on) { freshMovingSeeds_ = on; }
    void setMovingSamples(bool on) { movingSamples_ = on; }

private:
    std::uint64_t frameIndex_ = 0;
    int stillIndex_ = 0;
    int sampleIndex_ = 0;
    bool started_ = false;
    bool freshMovingSeeds_ = false;
    bool movingSamples_ = false;
    glm::vec2 jitter_{0.0f};
    glm::vec2 frameJitter_{0.0f}; // the frame's own, which setDirectSubsample(0, ...) restores
};

} // namespace bounce::gl
