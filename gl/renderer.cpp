#include "gl/renderer.h"

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
}

void Renderer::renderFrame(bool keepTimings)
{
    // Techniques size their buffers from the frame: a resized frame gets a technique made anew.
    if (frame_->width() != techniqueWidth_ || frame_->height() != techniqueHeight_) make(*info_, techniqueValues_);
    frame_->beginFrame();
    frame_->renderShadowMaps(timers_);
    frame_->renderGBuffer(timers_);
    frame_->renderDirect(timers_);
    frame_->clearIndirect();
    technique_->render(*frame_, timers_);
    frame_->composite(timers_);
    timers_.endFrame(keepTimings);
}

} // namespace bounce::gl
