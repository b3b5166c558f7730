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
    coarse_.reset();
    coarseTechnique_.reset();
    timers_.clear();
    stillReady_ = false;
}

void Renderer::setIndirectScale(int scale)
{
    if (scale < 1 || scale > 16) throw std::invalid_argument("indirect scale must be in 1..16");
    indirectScale_ = scale;
    coarse_.reset();
    coarseTechnique_.reset();
    stillReady_ = false;
}

void Renderer::advanceStill()
{
    const bool still = frame_->settings().accumulate && stillReady_ && frame_->version() == stillVersion_;
    stillVersion_ = frame_->version();
    stillReady_ = true;
    frame_->beginFrame(still);
}

bool Renderer::moveVertices(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals)
{
    if (!frame_->moveVertices(positions, normals)) return false;
    movedPositions_ = positions;
    movedNormals_ = normals;
    if (coarse_) coarse_->moveVertices(positions, normals);
    return true;
}

void Renderer::renderCoarseIndirect()
{
    const int w = (frame_->width() + indirectScale_ - 1) / indirectScale_;
    const int h = (frame_->height() + indirectScale_ - 1) / indirectScale_;
    if (!coarse_ || coarse_->width() != w || coarse_->height() != h) {
        FrameSettings s = frame_->settings();
        s.width = w;
        s.height = h;
        coarse_ = std::make_unique<Frame>(frame_->scene(), s);
        coarse_->setLights(frame_->gpuScene().punctualLights());
        coarseLights_ = frame_->version().lights;
        if (!movedPositions_.empty()) coarse_->moveVertices(movedPositions_, movedNormals_);
        coarseTechnique_ = info_->create(*coarse_, techniqueValues_);
        if (!upsample_) upsample_ = std::make_unique<JointUpsample>();
    }
    // The same view and lights as the full frame.
    coarse_->setCamera(frame_->camera());
    if (coarseLights_ != frame_->version().lights) {
        coarse_->setLights(frame_->gpuScene().punctualLights());
        coarseLights_ = frame_->version().lights;
    }
    coarse_->beginFrame();
    coarse_->setAreaLightsInDirect(frame_->areaLightsInDirect(), technique_->readsAreaShadowMaps());
    coarse_->renderShadowMaps(timers_);
    coarse_->renderGBuffer(timers_);
    // The viewer sees the full frame's direct light: the coarse frame draws its own only for a technique
    // that reads it.
    if (std::find(info_->reads.begin(), info_->reads.end(), GBufferChannel::Direct) != info_->reads.end())
        coarse_->renderDirect(timers_);
    coarse_->clearIndirect();
    coarseTechnique_->render(*coarse_, timers_);
    upsample_->run(*coarse_, *frame_, timers_);
}

void Renderer::renderFrame(bool keepTimings)
{
    // Techniques size their buffers from the frame: a resized frame gets a technique made anew.
    if (frame_->width() != techniqueWidth_ || frame_->height() != techniqueHeight_) make(*info_, techniqueValues_);
    advanceStill(); // beginFrame, still or moving
    frame_->setAreaLightsInDirect(!technique_->carriesEmittersLight(), technique_->readsAreaShadowMaps());
    frame_->renderShadowMaps(timers_);
    frame_->renderGBuffer(timers_);
    frame_->renderDirect(timers_);
    frame_->clearIndirect();
    if (indirectScale_ > 1)
        renderCoarseIndirect();
    else
        technique_->render(*frame_, timers_);
    // A technique that claims only direct light adds nothing: no composite pass, the result is the direct light.
    frame_->composite(timers_, info_->lightPaths != core::LightPaths::Direct);
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
