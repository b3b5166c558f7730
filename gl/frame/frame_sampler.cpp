#include "gl/frame/frame_sampler.h"

#include <algorithm>
#include <stdexcept>

#include "core/sampling.h"

namespace bounce::gl {

const std::vector<SampleStreamInfo>& FrameSampler::streams()
{
    // Halton's low dimensions (bases 2, 3, 11, 13, 17, 19) are the frame's, drawn by still frame; the
    // area lights' points a scrambled Sobol sequence (bases 5 and 7 lie on lines for their first points:
    // shadow_maps.cpp, areaSample). grb's bundles take Halton's sequence as the paper does (Sec. 4.3),
    // bases 2 and 3 for the directions and 5 and 7 for the offsets, and its atlas transfers the glossy
    // rotation's 17 and 19, at their own indices (the count of directions and of transfers). Streams of
    // their own measured worse: the directions and offsets as Owen-scrambled Sobol points, grb at 256x256
    // after 1200 directions against the path tracer's `full` (4x4-block means, emitter masked):
    // cornell-area with `emitters=frame` 4.5% -> 5.9% (means -1.0% -> -2.2%), cornell-spot 4.1% -> 4.2%.
    // The pixel jitter as antithetic pairs (a point, then its mirror through the pixel's centre: a mean
    // offset of zero after every second frame) measured worse too: `direct` on assets/setups/sponza-sun.json
    // at 256x256 without normal maps, 2, 3, 4, 8 and 16 still frames against `--paths direct` (4x4-block
    // means): 11.5%, 9.2%, 9.0%, 5.6%, 4.5% as Halton's points, 12.3%, 11.5%, 10.0%, 6.3%, 5.2% as pairs.
    static const std::vector<SampleStreamInfo> table = {
        {SampleStream::PixelJitter, "pixel jitter", SampleSequence::Halton, 0, 0, "Renderer (the G-buffer)"},
        {SampleStream::ShadowShift, "shadow-map shift", SampleSequence::Halton, 4, 0, "ShadowMaps"},
        {SampleStream::AreaLightPoint, "area-light point", SampleSequence::Sobol, 0, 1u, "ShadowMaps::areaSample"},
        {SampleStream::AreaGlossyRotation, "area glossy rotation", SampleSequence::Halton, 6, 0, "Frame::renderDirect"},
        {SampleStream::BundleDirection, "bundle direction", SampleSequence::Halton, 0, 0, "grb bundleDirection",
         "pixel jitter"},
        {SampleStream::BundleJitter, "bundle jitter", SampleSequence::Halton, 2, 0, "grb bundleJitter"},
        {SampleStream::AtlasAreaRotation, "atlas area rotation", SampleSequence::Halton, 6, 0,
         "grb RadianceAtlases::transfer", "area glossy rotation"},
        {SampleStream::DirectSubsample, "direct sub-sample", SampleSequence::Sobol, 0, 2u,
         "Frame::renderDirectSubsamples"},
    };
    return table;
}

const SampleStreamInfo& FrameSampler::info(SampleStream stream)
{
    const std::vector<SampleStreamInfo>& t = streams();
    const auto i = std::size_t(stream);
    if (i >= t.size() || t[i].stream != stream)
        throw std::logic_error("FrameSampler: the stream table is out of order");
    return t[i];
}

glm::vec2 FrameSampler::sample2(SampleStream stream, std::uint64_t index)
{
    const SampleStreamInfo& s = info(stream);
    if (s.sequence == SampleSequence::Sobol) return core::sobol2(std::uint32_t(index), s.seed);
    // A radical inverse within 2^-25 of 1 (indices past 2^24 in base 2) rounds to 1.0f: kept below it.
    constexpr float kBelowOne = 0x1.fffffep-1f;
    return {std::min(float(core::halton(s.firstDimension, index)), kBelowOne),
            std::min(float(core::halton(s.firstDimension + 1, index)), kBelowOne)};
}

void FrameSampler::advance(bool still)
{
    if (started_) ++frameIndex_;
    started_ = true;
    stillIndex_ = still ? stillIndex_ + 1 : 0;
    sampleIndex_ = stillIndex_ > 0 ? stillIndex_ : movingSamples_ ? int(frameIndex_ % 0x40000000u) + 1 : 0;
    jitter_ =
        stillIndex_ > 0 ? sample2(SampleStream::PixelJitter, std::uint64_t(sampleIndex_)) - 0.5f : glm::vec2(0.0f);
    frameJitter_ = jitter_;
}

void FrameSampler::setDirectSubsample(int sample, int perFrame)
{
    if (sample <= 0 || perFrame < 2) {
        jitter_ = frameJitter_;
        return;
    }
    const std::uint64_t index =
        std::uint64_t(std::max(sampleIndex_, 1) - 1) * std::uint64_t(perFrame - 1) + std::uint64_t(sample - 1);
    jitter_ = sample2(SampleStream::DirectSubsample, index) - 0.5f;
}

} // namespace bounce::gl
