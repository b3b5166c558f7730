// Final gather at the clusters' samples (section 3.3) and the interpolation of their irradiance to every
// pixel (section 3.4): glsl/technique/photon/photon_gather.{glsl,comp} and photon_interpolate.frag.
#pragma once

#include <cstdint>

#include "gl/frame/direct_lit_program.h"
#include "gl/frame/frame.h"
#include "gl/frame/ray_caster.h"
#include "gl/resource/buffer.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/timer.h"
#include "gl/technique/photon/illumination_cut.h"
#include "gl/technique/photon/photon_tracer.h"
#include "gl/technique/photon/photon_tree.h"
#include "gl/technique/photon/shading_clusters.h"

namespace bounce::gl {

struct FinalGatherSettings {
    int rays = 256;             // per sample (the paper: 250-500)
    int glossyRays = 4;         // per pixel with a glossy lobe and frame (GlossyGather; 0: the lobe's albedo)
    bool fullPhotonMap = false; // density estimation in every photon instead of the cut (Fig. 6's reference)
    int densityPhotons = 32;    // k, for fullPhotonMap
    std::uint32_t seed = 1;
    float causticAlpha = -1.0f; // hits whose lobe is this smooth do not reflect the lights (the caustic map's)
    bool cutGrid = false;       // Eq. 4's cut nodes from the cut's grid (IlluminationCut::useGrid), not the walk
};

class FinalGather {
public:
    FinalGather(const Frame& frame, const FinalGatherSettings& settings);

    // Gathers at every cluster's sample: writes each cluster's irradiance and R_j. Counters kCounterFirst
    // + 1 and + 2 receive the hits that only the fallback kernels reached, and those none reached.
    void gather(const Frame& frame, const RayCaster& caster, const PhotonTree& tree, const Buffer& photons,
                const IlluminationCut& cut, const ShadingClusters& clusters, float sceneSize, Buffer& counters,
                PassTimers& timers);
    std::uint32_t fallbackHits() const { return fallback_; }
    std::uint32_t uncoveredHits() const { return uncovered_; }

private:
    FinalGatherSettings settings_;
    DirectLitProgram program_;
    std::uint32_t fallback_ = 0, uncovered_ = 0;
};

// The glossy last bounce sampled at every pixel with a glossy lobe (photon_glossy.comp), added to what the
// interpolation wrote: `rays` directions from the lobe per pixel and frame, each bringing back a final-gather
// ray's radiance (direct light and the cut's photon light at its hit).
class GlossyGather {
public:
    GlossyGather(const Frame& frame, int rays, bool cutGrid);
    // Whether the scene has a lobe to sample and rays to sample it with: else run() does nothing and the
    // interpolation keeps the lobe's split-sum albedo.
    bool active() const { return rays_ > 0; }
    void run(Frame& frame, const RayCaster& caster, const PhotonTree& tree, const Buffer& photons,
             const IlluminationCut& cut, float sceneSize, PassTimers& timers);

private:
    int rays_;
    bool cutGrid_;
    DirectLitProgram program_;
};

// The caustic photon map (photon_caustic.comp): the caustic photons (L S+ D) near every pixel's surface
// point, cone-filtered within `radius` and reflected by its diffuse lobe, added to the pixel's indirect light.
// Active where the scene has a lobe no rougher than the tracer's causticRoughness.
class CausticMap {
public:
    // radius: of the density estimate, as a fraction of the scene's size.
    CausticMap(const Frame& frame, float causticRoughness, float radius);
    bool active() const { return active_; }
    // What the final gather's hits leave out for this map (FinalGatherSettings::causticAlpha).
    float gatherCausticAlpha() const { return active_ ? causticAlpha(roughness_) : -1.0f; }
    void run(Frame& frame, const PhotonTree& tree, const Buffer& photons, float sceneSize, PassTimers& timers);

private:
    bool active_;
    float roughness_, radius_;
    Program program_;
};

class Interpolation {
public:
    // asCompute: one invocation per pixel into the indirect texture (photon_interpolate.comp); else a
    // full-screen triangle (photon_interpolate.frag). The same arithmetic (photon_interpolate.glsl).
    // glossySampled: the glossy lobe is left out (GlossyGather adds it).
    explicit Interpolation(bool asCompute = defaultAsCompute(), bool glossySampled = false);
    // !preferFragmentPasses() (gl/probe/machine_probe.h): compute on a GPU, whose graphics units may be
    // few (an NVIDIA H200's fragment form took 9.6 ms at 1024x768, the compute form 0.58).
    static bool defaultAsCompute();
    // Writes the diffuse radiance of the interpolated irradiance into `target` (the frame's indirect
    // texture), or the irradiance itself with writeIrradiance (tests).
    void run(Frame& frame, const ShadingClusters& clusters, float maxError, bool ownSampleOnly, PassTimers& timers,
             bool writeIrradiance = false);

private:
    bool asCompute_;
    Program program_;
    Framebuffer framebuffer_;
    unsigned attached_ = 0;
};

} // namespace bounce::gl
