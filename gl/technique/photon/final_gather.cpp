#include "gl/technique/photon/final_gather.h"

#include <algorithm>
#include <string>
#include <vector>

#include "gl/context/context.h"
#include "gl/frame/bindings.h"
#include "gl/gl.h"
#include "gl/probe/machine_probe.h"
#include "gl/resource/dispatch.h"
#include "gl/resource/pass_state.h"
#include "gl/technique/photon/bindings.h"
#include "gl/technique/photon/photon_tracer.h"

namespace bounce::gl {

namespace {

// Only the kinds of light the scene has (as the frame's direct pass), and the density it gathers from.
std::vector<Define> gatherDefines(const Frame& frame, const FinalGatherSettings& s)
{
    std::vector<Define> d;
    const GpuScene& scene = frame.gpuScene();
    if (scene.punctualLightCount() > 0) d.push_back({"PUNCTUAL_LIGHTS", "1"});
    if (int(scene.lights().size()) > scene.punctualLightCount()) d.push_back({"AREA_LIGHTS", "1"});
    if (s.fullPhotonMap) {
        d.push_back({"DENSITY_PHOTONS", "1"});
        d.push_back({"NEAREST_K", std::to_string(s.densityPhotons)});
    }
    return d;
}

} // namespace

FinalGather::FinalGather(const Frame& frame, const FinalGatherSettings& settings)
    : settings_(settings),
      program_(Program::compute("photon.gather", "technique/photon/photon_gather.comp", gatherDefines(frame, settings)))
{}

void FinalGather::gather(const Frame& frame, const RayCaster& caster, const PhotonTree& tree, const Buffer& photons,
                         const IlluminationCut& cut, const ShadingClusters& clusters, float sceneSize, Buffer& counters,
                         PassTimers& timers)
{
    auto t = timers.scope("gather");
    const std::uint32_t zero[2] = {0, 0};
    counters.update((kCounterFirst + 1) * 4, sizeof zero, zero);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (clusters.count() == 0) {
        fallback_ = uncovered_ = 0;
        return;
    }
    frame.bindSceneData();
    caster.bind();
    tree.bind(program_);
    photons.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTONS);
    cut.bind();
    clusters.bind();
    counters.bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_PHOTON_COUNTERS);
    program_.set("punctualLightCount", frame.gpuScene().punctualLightCount());
    program_.set("lightCount", frame.shadowMaps().lightCount());
    // One shadow-map tap per hit: hundreds of rays average a sample's light, PCF would only cost.
    frame.shadowMaps().setPcfUniforms(program_, 0);
    program_.set("clusterCount", clusters.count());
    program_.set("gatherRays", unsigned(std::max(settings_.rays, 1)));
    program_.set("rayEpsilon", 1e-5f * sceneSize);
    program_.set("minDistance", 1e-4f * sceneSize);
    program_.set("maxDistance", sceneSize);
    program_.set("seed", settings_.seed);
    program_.use();
    glDispatchCompute(clusters.count(), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    std::uint32_t hits[2] = {0, 0};
    counters.download((kCounterFirst + 1) * 4, sizeof hits, hits);
    fallback_ = hits[0];
    uncovered_ = hits[1];
}

Interpolation::Interpolation(bool asCompute)
    : asCompute_(asCompute),
      program_(asCompute ? Program::compute("photon.interpolate", "technique/photon/photon_interpolate.comp")
                         : Program::graphics("photon.interpolate", "frame/fullscreen.vert",
                                             "technique/photon/photon_interpolate.frag"))
{} // the fragment form's framebuffer is made in run(), on the frame's indirect texture; the compute form has none

bool Interpolation::defaultAsCompute()
{
    return !preferFragmentPasses();
}

void Interpolation::run(Frame& frame, const ShadingClusters& clusters, float maxError, bool ownSampleOnly,
                        PassTimers& timers, bool writeIrradiance)
{
    auto t = timers.scope("interpolate");
    if (!asCompute_ && attached_ != frame.indirect().id()) {
        framebuffer_ = Framebuffer("photon.interpolate");
        framebuffer_.attach(GL_COLOR_ATTACHMENT0, frame.indirect());
        framebuffer_.checkComplete();
        attached_ = frame.indirect().id();
    }
    if (!asCompute_) PassState::fullscreen(framebuffer_, frame.width(), frame.height()).apply();
    frame.bindGBuffer();
    clusters.bind();
    clusters.bindPointTree(program_);
    clusters.clusterOfPixel().bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_CLUSTER_OF_PIXEL);
    program_.set("viewport", glm::ivec2(frame.width(), frame.height()));
    program_.set("clusterCount", clusters.count());
    program_.set("maxError", maxError);
    program_.set("ownSampleOnly", ownSampleOnly ? 1 : 0);
    program_.set("writeIrradiance", writeIrradiance ? 1 : 0);
    program_.set("cameraPosition", frame.camera().position);
    if (asCompute_) {
        frame.indirect().bindImage(0, GL_WRITE_ONLY);
        dispatchCompute(program_, {frame.width(), frame.height(), 1}, {8, 8, 1});
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
        return;
    }
    program_.use();
    frame.drawFullscreen();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

} // namespace bounce::gl
