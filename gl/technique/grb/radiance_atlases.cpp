#include "gl/technique/grb/radiance_atlases.h"

#include "core/sampling.h"
#include "gl/frame/bindings.h"
#include "gl/gl.h"
#include "gl/resource/pass_state.h"
#include "gl/technique/grb/bindings.h"

namespace bounce::gl {

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

void RadianceAtlases::seed(const Frame& frame, const GrbAtlas& atlas, PassTimers& timers)
{
    const float zero[4] = {0, 0, 0, 0};
    seed_.clear(0, zero);
    if (!settings_.punctual) return;
    auto t = timers.scope("seed");
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
    auto t = timers.scope("transfer");
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
        transfer_.set("lightCount", frame.shadowMaps().lightCount());
        // The emitters' points rotate from direction to direction (Halton dimensions 6 and 7 of the count
        // of transfers so far), so that their sum over directions covers each emitter evenly.
        const auto n = std::uint64_t(++transfers_);
        transfer_.set("areaRotation", glm::vec2(float(core::halton(6, n)), float(core::halton(7, n))));
    }
    frame.shadowMaps().setPcfUniforms(transfer_, frame.settings().pcfRadius);
    transfer_.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    current_ = receiver;
}

} // namespace bounce::gl
