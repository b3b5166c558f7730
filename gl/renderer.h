// One whole frame, the same for the CLI, the demo, the benchmark and the tests: the frame's passes, the
// technique's indirect light, the composite. Owns the frame and the technique.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/scene.h"
#include "gl/frame/frame.h"
#include "gl/frame/temporal_reuse.h"
#include "gl/technique/technique.h"

namespace bounce::gl {

class Renderer {
public:
    // frameValues: frameParams() values; techniqueValues: the technique's declared parameters.
    Renderer(const core::Scene& scene, const std::string& technique, const ParamValues& frameValues,
             const ParamValues& techniqueValues, int width, int height);

    // A technique that is not in the registry (tests): `info` must outlive the renderer.
    Renderer(const core::Scene& scene, const TechniqueInfo& info, const ParamValues& frameValues,
             const ParamValues& techniqueValues, int width, int height);

    void renderFrame(bool keepTimings = true);
    void setTechnique(const std::string& technique, const ParamValues& techniqueValues);
    // New values for the running technique: when only ParamUpdate::Uniform parameters changed they go to
    // Technique::setUniforms() (no shader is recompiled), else the technique is made anew. Returns true
    // when it was made anew.
    bool setTechniqueValues(const ParamValues& techniqueValues);
    // Progressive techniques: start accumulating again (warm-up frames are not accumulation steps).
    void restartAccumulation()
    {
        technique_->restart();
        stillReady_ = false;
    }
    int accumulatedSteps() const { return technique_->accumulatedSteps(); }

    // Still frames (frame parameter `accumulate`): while the frame's version (scene, lights, camera) and the
    // technique hold, each frame samples its pixels at another Halton (2, 3) point inside the pixel and
    // result() is the mean of the frames since the view was last changed (Frame::accumulate), which
    // converges to the box-filtered pixels the path tracer computes. The count of those frames (0 while
    // the view moves: nothing is averaged, nothing is jittered).
    // The frame's sampler holds it (FrameSampler::stillIndex); its jitter is Halton (2, 3) point i less the
    // centre, so that the offsets are stratified over the pixel for any count of frames.
    int stillFrames() const { return frame_->sampler().stillIndex(); }

    // Indirect light at 1/scale of the frame's resolution (the demo's frame budget while the camera or a
    // light moves): the same technique instance runs on the frame's coarse targets of ceil(w/scale) x
    // ceil(h/scale) (Frame::beginIndirect: a G-buffer rasterised at that size from the same camera, the same
    // shadow maps, GPU scene and ray caster), and its indirect light reaches the full frame through joint
    // bilateral upsampling (gl/frame/joint_upsample.h); the G-buffer and direct light the viewer sees stay
    // at full resolution. What the technique built that does not depend on the camera (ray-bundle atlases,
    // point hierarchies, clusters, compiled programs) survives a change of scale, and a progressive one
    // keeps accumulating through it. Throws std::invalid_argument outside 1..16.
    // A technique whose indirect light would not get cheaper (Technique::indirectScales) is drawn at full
    // resolution at every scale.
    void setIndirectScale(int scale);
    int indirectScale() const { return indirectScale_; }
    // Whether the running technique's indirect light follows setIndirectScale().
    bool indirectScales() const { return technique_->indirectScales(); }
    // The resolution the indirect light is computed at.
    int indirectWidth() const { return (frame_->width() + drawnScale() - 1) / drawnScale(); }
    int indirectHeight() const { return (frame_->height() + drawnScale() - 1) / drawnScale(); }

    // Temporal reuse (frame parameter `temporal`, off unless set): the indirect light of a
    // technique that declares TechniqueInfo::temporalReuse is blended, at the resolution it is computed at
    // (before the upsampling of setIndirectScale), with its own history reprojected through the previous
    // camera (gl/frame/temporal_reuse.h), and moving frames draw new samples each frame
    // (FrameSampler::hashSeed). A technique switch, a change of scale or of size drops the history; a change
    // of lights or geometry does not (the reprojection's tests and the clamp absorb it, with a lag).
    bool temporalReuse() const { return frame_->settings().temporal && info_->temporalReuse; }

    Frame& frame() { return *frame_; }
    bool moveVertices(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals)
    {
        return frame_->moveVertices(positions, normals);
    }
    const TechniqueInfo& technique() const { return *info_; }
    // The technique writes the emitters' reflected light into indirect() (Technique::carriesEmittersLight).
    bool indirectCarriesEmittersLight() const { return technique_->carriesEmittersLight(); }
    const ParamValues& techniqueValues() const { return techniqueValues_; }
    const ParamValues& frameValues() const { return frameValues_; }
    PassTimers& timers() { return timers_; }
    std::vector<Counter> counters() const { return technique_->counters(); }
    // The frame's own: the shadow-map texels drawn this frame and the largest side of a view (a spot's or
    // point light's from its footprint on screen, gl/frame/shadow_maps.h).
    std::vector<Counter> frameCounters() const;
    nlohmann::json notes() const { return technique_->notes(); }
    core::Image image() const { return frame_->read(frame_->result()); }

private:
    void make(const TechniqueInfo& info, const ParamValues& techniqueValues);
    void reuseDirectLight();
    int drawnScale() const { return technique_->indirectScales() ? indirectScale_ : 1; }
    std::unique_ptr<Frame> frame_;
    const TechniqueInfo* info_ = nullptr;
    std::unique_ptr<Technique> technique_;
    ParamValues frameValues_, techniqueValues_;
    PassTimers timers_;
    TemporalReuse temporal_; // frame parameter `temporal`, for a technique that declares temporalReuse
    // Frame parameters `temporal` and `temporal.direct`: the frame's direct light in moving frames, for every
    // technique, sampled anew each frame (FrameSampler::sampleIndex); its history is dropped when the lights
    // change (their version below).
    TemporalReuse temporalDirect_;
    std::uint64_t temporalDirectLights_ = 0;
    int techniqueWidth_ = 0, techniqueHeight_ = 0;
    int indirectScale_ = 1;
    bool stillReady_ = false; // the last frame's version below is comparable (no technique change since)
    FrameVersion stillVersion_;
    void advanceStill();
};

} // namespace bounce::gl
