#include "gl/renderer.h"

#include <algorithm>

#include <stdexcept>

namespace bounce::gl {

Renderer::Renderer(const core::Scene& scene, const std::string& technique, const ParamValues& frameValues,
                   const ParamValues& techniqueValues, int width, int height)
    : frame_(std::make_unique<Frame>(scene, frameSettingsFrom(frameValues, width, height))), frameValues_(frameValues)
{
    setTechnique(technique, techniqueValues);
}

Renderer::Renderer(const core::Scene& scene, const TechniqueInfo& info, const ParamValues& frameValues,
                   const ParamValues& techniqueValues, int width, int height)
    : frame_(std::make_unique<Frame>(scene, frameSettingsFrom(frameValues, width, height))), frameValues_(frameValues)
{
    make(info, techniqueValues);
}

void Renderer::setTechnique(const std::string& technique, const ParamValues& techniqueValues)
{
    make(findTechnique(technique), techniqueValues);
}

bool Renderer::setTechniqueValues(const ParamValues& techniqueValues)
{
    bool uniformsOnly = true;
    for (const std::string& name : techniqueValues.changed(techniqueValues_)) {
        const ParamDecl* decl = nullptr;
        for (const ParamDecl& d : info_->params)
            if (d.name == name) decl = &d;
        uniformsOnly &= decl && decl->update == ParamUpdate::Uniform;
    }
    if (!uniformsOnly) {
        make(*info_, techniqueValues);
        return true;
    }
    techniqueValues_ = techniqueValues;
    technique_->setUniforms(techniqueValues_);
    stillReady_ = false;
    return false;
}

void Renderer::make(const TechniqueInfo& info, const ParamValues& techniqueValues)
{
    info_ = &info;
    techniqueValues_ = techniqueValues;
    technique_ = info_->create(*frame_, techniqueValues_);
    techniqueWidth_ = frame_->width();
    techniqueHeight_ = frame_->height();
    timers_.clear();
    temporal_.reset();
    temporalDirect_.reset();
    stillReady_ = false;
}

void Renderer::reuseDirectLight()
{
    // A light change makes every history of the direct light wrong at once: it starts over.
    if (frame_->version().lights != temporalDirectLights_) temporalDirect_.reset();
    temporalDirectLights_ = frame_->version().lights;
    temporalDirect_.settings.alpha = frame_->settings().temporalAlpha;
    temporalDirect_.settings.catmullRom = frame_->settings().temporalCatmullRom;
    // With emitting triangles, only the share of their exact light that reaches each pixel is averaged
    // (Frame::areaRatioDrawn): the rest of the light is exact in every frame. Unclamped: every pixel of a
    // frame takes its shadows from the same point on each emitter, so one frame's 3x3 neighbourhood holds
    // that point's shadow only, and a clamp to it kept the penumbrae from averaging (cornell-area along
    // bench/paths/cornell-orbit.json: 40% with the clamp against 15% without).
    if (frame_->areaRatioDrawn()) {
        temporalDirect_.settings.clamp = false;
        temporalDirect_.apply(*frame_, {&frame_->areaVisibility()}, timers_);
        frame_->resolveAreaRatio(timers_);
        return;
    }
    // Point, spot and directional lights with shadow rays: every frame's light is exact at its pixels'
    // centres, nothing stochastic to average, so the history only antialiases and is clamped as temporal
    // antialiasing clamps (temporal.clamp). Unclamped, the bilinear resampling of each frame spread a shadow
    // edge that moves over the screen into a trail a few pixels wide (the Sponza walk, 128x128: frame 40
    // read 29.5% unclamped and 22.8% clamped). Shifted shadow maps (shadow.still=maps) keep it unclamped:
    // their shift is one per frame, as the emitters' point is.
    temporalDirect_.settings.clamp = frame_->settings().temporalClamp && frame_->settings().stillRayShadows;
    temporalDirect_.apply(*frame_, {&frame_->direct()}, timers_);
}

void Renderer::setIndirectScale(int scale)
{
    if (scale < 1 || scale > 16) throw std::invalid_argument("indirect scale must be in 1..16");
    const int drawn = drawnScale();
    indirectScale_ = scale;
    if (drawnScale() != drawn) stillReady_ = false; // the still mean starts again from the first frame at this scale
}

void Renderer::advanceStill()
{
    const bool still = frame_->settings().accumulate && stillReady_ && frame_->version() == stillVersion_;
    stillVersion_ = frame_->version();
    stillReady_ = true;
    frame_->beginFrame(still);
}

void Renderer::renderFrame(bool keepTimings)
{
    // Techniques size their buffers from the frame: a resized frame gets a technique made anew.
    if (frame_->width() != techniqueWidth_ || frame_->height() != techniqueHeight_) make(*info_, techniqueValues_);
    advanceStill(); // beginFrame, still or moving
    frame_->setAreaLightsInDirect(!technique_->carriesEmittersLight(), technique_->readsAreaShadowMaps());
    frame_->setShadowMapsRead(technique_->readsShadowMaps(*frame_));
    frame_->renderShadowMaps(timers_);
    frame_->renderDirectSubsamples(timers_); // *.directSamples > 1: the further points' direct light
    frame_->renderGBuffer(timers_);
    frame_->renderDirect(timers_);
    if (frame_->settings().temporal && frame_->settings().temporalDirect && frame_->sampler().stillIndex() == 0)
        reuseDirectLight();
    // At a coarser scale the frame draws its own direct light at that scale only for a technique that
    // reads it: the viewer sees the full-resolution direct light.
    const bool readsDirect =
        std::find(info_->reads.begin(), info_->reads.end(), GBufferChannel::Direct) != info_->reads.end();
    frame_->beginIndirect(drawnScale(), timers_, readsDirect);
    technique_->render(*frame_, timers_);
    if (temporalReuse()) {
        temporal_.settings.alpha = frame_->settings().temporalAlpha;
        temporal_.settings.clamp = frame_->settings().temporalClamp;
        temporal_.settings.catmullRom = frame_->settings().temporalCatmullRom;
        temporal_.apply(*frame_, {&frame_->indirect()}, timers_);
    }
    frame_->endIndirect(timers_);
    // A technique that claims only direct light adds nothing: no composite pass, the result is the direct light.
    frame_->composite(timers_, info_->lightPaths != core::LightPaths::Direct);
    frame_->antialiasEdges(timers_);
    frame_->accumulate(timers_, info_->progressive);
    timers_.endFrame(keepTimings);
}

std::vector<Counter> Renderer::frameCounters() const
{
    const ShadowMaps& s = frame_->shadowMaps();
    int largest = 0;
    for (std::size_t i = 0; i < s.views().size(); ++i)
        if (s.renders(i)) largest = std::max(largest, s.sides()[i]);
    return {{"shadow.texels", s.renderedTexels()}, {"shadow.largestSide", double(largest)}};
}

} // namespace bounce::gl
