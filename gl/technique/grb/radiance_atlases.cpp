#include "gl/technique/grb/radiance_atlases.h"

#include "gl/frame/bindings.h"
#include "gl/frame/frame_sampler.h"
#include "gl/frame/shader_costs.h"
#include "gl/gl.h"
#include "gl/resource/pass_state.h"
#include "gl/technique/grb/bindings.h"

namespace bounce::gl {

namespace {

// transfer.frag per atlas texel: its position (empty ones stop there). Per filled texel (the atlas counted
// them): its normal, chart, base colour, material and both sender sums, bundleSender with charts, one
// sender's radiance (a bound: every receiver finds one), brdfParams and the transmission, two RGBA32F out;
// GLOSSY (a bound: every texel glossy) the lobe towards the next direction and an RGBA16F out, with
// AREA_GLOSSY per emitting triangle 16 points (about 2500 flops, its light and polygon) and a shadow lookup
// (the shader's is per mesh: a bound), with PUNCTUAL_LIGHTS per light the irradiance, the lobe, its light
// and a shadow lookup.
PassCost transferCost(const RadianceAtlases& radiance, const Frame& frame, const GrbAtlas& atlas,
                      const KBuffer& kbuffer)
{
    const RadianceSettings& s = radiance.settings();
    const PassCost sender = kbuffer.bundleSenderCost(true), sent = radiance.senderRadianceCost();
    const PassCost shadow = shadowLookupCost(frame);
    const double punctual = s.punctual ? frame.gpuScene().punctualLightCount() : 0.0;
    const double area = s.areaGlossy ? frame.lights().count() - frame.gpuScene().punctualLightCount() : 0.0;
    PassCost r; // per filled texel
    r.flops = 95 + sender.flops + sent.flops;
    r.fetches = 5 + sender.fetches + sent.fetches;
    r.bytesRead = 5 * 16 + 64 + sender.bytesRead + sent.bytesRead;
    r.bytesWritten = 2 * 16;
    if (s.glossy) {
        r.flops += 110 + area * 2500 + punctual * 125 + (area + punctual) * shadow.flops;
        r.fetches += (area + punctual) * shadow.fetches;
        r.bytesRead += (area + punctual) * shadow.bytesRead;
        r.bytesWritten += 8;
        r.uniformWords = area * (16 + 12) + punctual * 16 + (area + punctual) * shadow.uniformWords;
    }
    const double filled = double(atlas.filledTexels());
    PassCost c;
    c.flops = 1;
    c.fetches = 1;
    c.bytesRead = 16;
    c.flopsFixed = filled * r.flops;
    c.fetchesFixed = filled * r.fetches;
    c.bytesFixed = filled * (r.bytesRead + r.bytesWritten);
    c.uniformWordsFixed = filled * r.uniformWords;
    return c;
}

} // namespace

RadianceAtlases::RadianceAtlases(const GrbAtlas& atlas, const KBuffer& kbuffer, const RadianceSettings& settings)
    : settings_(settings),
      width_(atlas.width()),
      height_(atlas.height()),
      fbo_{Framebuffer("grb.radiance.fbo0"), Framebuffer("grb.radiance.fbo1")},
      seedFbo_("grb.seed.fbo"),
      vao_("grb.radiance.fullscreen")
{
    seed_ = Texture::create2D("grb.atlas.seed", GL_RGBA32F, width_, height_);
    seedFbo_.attach(GL_COLOR_ATTACHMENT0, seed_);
    seedFbo_.checkComplete();
    for (int i = 0; i < 2; ++i) {
        const std::string n = std::to_string(i);
        direct_[i] = Texture::create2D("grb.atlas.direct" + n, GL_RGBA32F, width_, height_);
        indirect_[i] = Texture::create2D("grb.atlas.indirect" + n, GL_RGBA32F, width_, height_);
        fbo_[i].attach(GL_COLOR_ATTACHMENT0, direct_[i]);
        fbo_[i].attach(GL_COLOR_ATTACHMENT1, indirect_[i]);
        if (settings.glossy) {
            glossy_[i] = Texture::create2D("grb.atlas.glossy" + n, GL_RGBA16F, width_, height_);
            fbo_[i].attach(GL_COLOR_ATTACHMENT2, glossy_[i]);
            fbo_[i].setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2});
        } else {
            fbo_[i].setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1});
        }
        fbo_[i].checkComplete();
    }
    std::vector<Define> d = defines();
    for (const Define& r : kbuffer.readerDefines()) d.push_back(r);
    transfer_ = Program::graphics("grb.transfer", "frame/fullscreen.vert", "technique/grb/transfer.frag", d);
    if (settings.punctual)
        seedProgram_ = Program::graphics("grb.seed", "frame/fullscreen.vert", "technique/grb/direct_seed.frag",
                                         {{"ATLAS_TEXTURES", "1"}});
    clear();
}

std::vector<Define> RadianceAtlases::defines() const
{
    std::vector<Define> d = {{"ATLAS_TEXTURES", "1"}};
    if (settings_.glossy) d.push_back({"GLOSSY", "1"});
    if (settings_.punctual) d.push_back({"PUNCTUAL_LIGHTS", "1"});
    if (settings_.areaGlossy) d.push_back({"AREA_GLOSSY", "1"});
    if (settings_.interleaved) d.push_back({"INTERLEAVED", "1"});
    return d;
}

void RadianceAtlases::clear()
{
    const float zero[4] = {0, 0, 0, 0};
    seed_.clear(0, zero);
    for (int i = 0; i < 2; ++i) {
        direct_[i].clear(0, zero);
        indirect_[i].clear(0, zero);
        if (settings_.glossy) glossy_[i].clear(0, zero);
    }
    current_ = 0;
}

void RadianceAtlases::bindSender() const
{
    seed_.bind(UNIT_GRB_SEED);
    direct_[current_].bind(UNIT_GRB_SENDER_DIRECT);
    indirect_[current_].bind(UNIT_GRB_SENDER_INDIRECT);
    if (settings_.glossy) glossy_[current_].bind(UNIT_GRB_SENDER_GLOSSY);
}

PassCost RadianceAtlases::senderRadianceCost() const
{
    // Its position, normal and base colour (RGBA32F) and material (64 bytes), the face normal unpacked and
    // brdfParams; interleaved, the transmission and the seed, direct and indirect sums; one bounce, the
    // transmission and the seed alone; in a glossy scene either way the glossy transfer texel (RGBA16F).
    const bool interleaved = settings_.interleaved, glossy = settings_.glossy;
    PassCost c;
    c.flops = 60 + (interleaved ? 42 : 32) + (glossy ? 3 : 0);
    c.fetches = 3 + (interleaved ? 3 : 1) + (glossy ? 1 : 0);
    c.bytesRead = 3 * 16 + 64 + (interleaved ? 3 * 16 : 16) + (glossy ? 8 : 0);
    return c;
}

void RadianceAtlases::seed(const Frame& frame, const GrbAtlas& atlas, PassTimers& timers)
{
    const float zero[4] = {0, 0, 0, 0};
    seed_.clear(0, zero);
    if (!settings_.punctual) return;
    // direct_seed.frag per atlas texel: its position (empty ones stop there); per filled texel (the atlas
    // counted them) its normal, base colour and material, brdfParams, and per punctual light the irradiance,
    // the transmission and a shadow lookup (a bound: every texel lit by every light), one RGBA32F out.
    const double filled = double(atlas.filledTexels()), lights = frame.gpuScene().punctualLightCount();
    const PassCost shadow = shadowLookupCost(frame);
    PassCost cost;
    cost.flops = 1;
    cost.fetches = 1;
    cost.bytesRead = 16;
    cost.flopsFixed = filled * (32 + lights * (65 + shadow.flops));
    cost.fetchesFixed = filled * (2 + lights * shadow.fetches);
    cost.bytesFixed = filled * (2 * 16 + 64 + lights * shadow.bytesRead + 16);
    cost.uniformWordsFixed = filled * lights * (16 + shadow.uniformWords);
    auto t = timers.scope("seed", cost);
    t.expectFragments(width_, height_); // every atlas texel, filled or not
    PassState::fullscreen(seedFbo_, width_, height_).apply();
    frame.bindSceneData();
    atlas.bind();
    seedProgram_.set("punctualLightCount", frame.gpuScene().punctualLightCount());
    frame.shadowMaps().setPcfUniforms(seedProgram_, frame.settings().pcfRadius);
    seedProgram_.set("atlasWidth", width_);
    seedProgram_.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void RadianceAtlases::transfer(const Frame& frame, const GrbAtlas& atlas, const KBuffer& kbuffer,
                               const BundleView& view, const glm::vec3& next, PassTimers& timers)
{
    auto t = timers.scope("transfer", transferCost(*this, frame, atlas, kbuffer));
    t.expectFragments(width_, height_);
    const int receiver = 1 - current_;
    PassState::fullscreen(fbo_[receiver], width_, height_).apply();
    frame.bindSceneData();
    atlas.bind();
    kbuffer.bindForRead();
    bindSender();
    KBuffer::setBundleUniforms(transfer_, view);
    transfer_.set("nextDir", next);
    transfer_.set("atlasWidth", width_);
    transfer_.set("punctualLightCount", frame.gpuScene().punctualLightCount());
    if (settings_.areaGlossy) {
        transfer_.set("lightCount", frame.lights().count());
        // The emitters' points rotate from direction to direction (the stream AtlasAreaRotation at the count
        // of transfers so far), so that their sum over directions covers each emitter evenly.
        const auto n = std::uint64_t(++transfers_);
        transfer_.set("areaRotation", FrameSampler::sample2(SampleStream::AtlasAreaRotation, n));
    }
    frame.shadowMaps().setPcfUniforms(transfer_, frame.settings().pcfRadius);
    transfer_.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    current_ = receiver;
}

} // namespace bounce::gl
