#include "gl/technique/photon/photon_technique.h"

#include <algorithm>
#include <memory>
#include <numeric>

#include <glm/glm.hpp>

#include "gl/frame/ray_caster.h"
#include "gl/technique/photon/final_gather.h"
#include "gl/technique/photon/illumination_cut.h"
#include "gl/technique/photon/photon_tracer.h"
#include "gl/technique/photon/photon_tree.h"
#include "gl/technique/photon/shading_clusters.h"

namespace bounce::gl {

namespace {

struct PhotonSettings {
    PhotonTracerSettings tracer;
    int leafPhotons = 1;
    IlluminationCutSettings cut;
    int cutGridCells = IlluminationCut::kMaxGridCells; // 0: the gather walks the tree above the cut
    ShadingClusterSettings clusters;
    FinalGatherSettings gather;
    float interpolationError = 0.2f;
    bool interpolateAsCompute = true;
    float causticRadius = 0.01f; // of the caustic map's estimate, per scene size
};

// The gather's settings, with the hits' near-specular reflections of the lights left to the caustic map.
FinalGatherSettings gatherSettings(const FinalGatherSettings& s, const CausticMap& caustic)
{
    FinalGatherSettings g = s;
    g.causticAlpha = caustic.gatherCausticAlpha();
    return g;
}

class Photon final : public Technique {
public:
    Photon(Frame& frame, const PhotonSettings& s)
        : settings_(s),
          counters_("photon.counters", kCounterSlots * 4),
          tracer_(s.tracer),
          tree_(s.leafPhotons),
          clusters_(s.clusters),
          caustic_(frame, s.tracer.causticRoughness, s.causticRadius),
          gather_(frame, gatherSettings(s.gather, caustic_)),
          glossy_(frame, s.gather.glossyRays, s.gather.cutGrid),
          interpolation_(s.interpolateAsCompute, glossy_.active())
    {
        const core::Bounds& b = frame.gpuScene().bounds();
        sceneSize_ = b.empty() ? 1.0f : std::max(glm::length(b.extent()), 1e-30f);
        if (s.gather.cutGrid) cut_.useGrid(b, s.cutGridCells);
    }

    void render(Frame& frame, PassTimers& timers) override
    {
        const RayCaster& caster = frame.rayCaster(); // the BVH of the geometry as it is now
        tracer_.trace(frame, caster, counters_, timers);
        tree_.build(tracer_.photons(), tracer_.storedCount(), sceneSize_ / 4096.0f, timers);
        cut_.build(tree_, tracer_.photons(), settings_.cut, counters_, timers);
        clusters_.cluster(frame, sceneSize_, counters_, timers);
        gather_.gather(frame, caster, tree_, tracer_.photons(), cut_, clusters_, sceneSize_, counters_, timers);
        const bool everyPixel = settings_.clusters.everyPixel;
        if (!everyPixel && clusters_.count() > 0) {
            // The tree of samples: its kernels' work from the cluster count (ShadingClusters::addPointTreeWork).
            auto t = timers.scope("sample-tree");
            clusters_.buildPointTree(true, counters_);
            clusters_.addPointTreeWork(t);
        }
        interpolation_.run(frame, clusters_, settings_.interpolationError, everyPixel, timers);
        glossy_.run(frame, caster, tree_, tracer_.photons(), cut_, sceneSize_, timers);
        caustic_.run(frame, tree_, tracer_.photons(), sceneSize_, timers);
    }

    void restart() override { clusters_.restart(); }

    std::vector<Counter> counters() const override
    {
        return {
            {"photons.emitted", double(settings_.tracer.photons)},
            {"photons.stored", double(tracer_.storedCount())},
            {"photons.capacity", double(tracer_.capacity())},
            {"photons.projectionCoverage", projectionCoverage()},
            {"photons.maxPowerScale", maxPowerScale()},
            {"tree.depth", double(tree_.depth())},
            {"cut.eMin", double(cut_.eMin())},
            {"cut.coarseSize", double(cut_.coarseSize())},
            {"cut.size", double(cut_.size())},
            {"cut.splits", splitCount()},
            {"cut.gridCells", double(cut_.gridDims().x) * cut_.gridDims().y * cut_.gridDims().z},
            {"cut.gridEntries", double(cut_.gridEntries())},
            {"clusters", double(clusters_.nonEmpty())},
            {"clusters.seeds", double(clusters_.seedsPlaced())},
            {"clusters.reused", double(clusters_.survivors())},
            {"clusters.iterations", double(clusters_.iterationsRun())},
            {"gather.rays", double(clusters_.nonEmpty()) * double(settings_.gather.rays)},
            {"gather.fallbackHits", double(gather_.fallbackHits())},
            {"gather.uncoveredHits", double(gather_.uncoveredHits())},
        };
    }

private:
    // The share of the directional lights' projection maps whose cells send photons (0 without one).
    double projectionCoverage() const
    {
        double marked = 0.0, all = 0.0;
        for (const ProjectionMap& m : tracer_.projectionMaps()) {
            marked += double(m.cells.size());
            all += double(m.gridSize) * m.gridSize;
        }
        return all > 0.0 ? marked / all : 0.0;
    }

    // Guided emission: the largest factor on a directional light's power per photon, that of a cell with one
    // copy in the emission list (entries / cells; 1 unguided or without a directional light).
    double maxPowerScale() const
    {
        double scale = 1.0;
        for (const ProjectionMap& m : tracer_.projectionMaps())
            if (!m.copies.empty())
                scale =
                    std::max(scale, std::accumulate(m.copies.begin(), m.copies.end(), 0.0) / double(m.cells.size()));
        return scale;
    }

    double splitCount() const
    {
        double n = 0.0;
        for (std::uint32_t s : cut_.splitsPerIteration()) n += s;
        return n;
    }

    PhotonSettings settings_;
    Buffer counters_;
    PhotonTracer tracer_;
    PhotonTree tree_;
    IlluminationCut cut_;
    ShadingClusters clusters_;
    CausticMap caustic_;
    FinalGather gather_;
    GlossyGather glossy_;
    Interpolation interpolation_;
    float sceneSize_ = 1.0f;
};

} // namespace

TechniqueInfo photonTechniqueInfo()
{
    TechniqueInfo info;
    info.name = "photon";
    info.paper = "Wang, Wang, Zhou, Pan & Bao 2009";
    info.lightPaths = core::LightPaths::Full;
    info.temporalReuse = true; // photons and final-gather rays drawn anew each moving frame under `temporal`
    info.summary = "photon mapping on the GPU: final gather at k-means shading clusters from an illumination cut of "
                   "the photon tree, interpolated to every pixel";
    info.passes = {
        {"photon-trace", "photons from every light through the BVH, Russian roulette, stored from the second surface",
         ""},
        {"photon-sort", "photons put in path order, sorted by Hilbert index, then put in kd order (on the CPU)", ""},
        {"photon-tree", "the linear hierarchy over the sorted photons with Eq. 3 per node", ""},
        {"cut", "E_min, the valid cut, its refinement and the irradiance cached per cut node", ""},
        {"kmeans", "quadtree seeding and k-means shading clusters with their samples", ""},
        {"gather", "final gather at every cluster's sample through the cut", ""},
        {"sample-tree", "the tree of the clusters' samples, which the interpolation walks", "gatherAt=clusters"},
        {"interpolate", "each pixel's irradiance interpolated from the samples near it (section 3.4)", ""},
        {"glossy", "the glossy last bounce sampled from the lobe at every pixel with one, through the cut", ""},
        {"caustic", "the caustic photons (L S+ D) near every pixel, where the scene has a near-specular lobe", ""},
    };
    info.reads = {GBufferChannel::Position, GBufferChannel::Normal, GBufferChannel::Diffuse, GBufferChannel::Specular};
    info.params = {
        {"photons", ParamType::Int, 65536, 0, 16777216, "photon paths emitted per frame (split among lights by power)"},
        {"maxBounces", ParamType::Int, 16, 1, 64, "surfaces one photon path may reach"},
        {"russianRoulette", ParamType::Bool, 1, 0, 1, "end photon paths by Russian roulette (0: only at maxBounces)"},
        choiceParam("firstSurfaceRoulette", {"auto", "all", "none"}, 0,
                    "Russian roulette at a photon path's first surface (not stored: its light is direct): auto at "
                    "every light's but a directional light's, whose guided photons it would mostly end there"),
        {"projectionMap", ParamType::Bool, 1, 0, 1,
         "a directional light's photons leave only from where its projection map meets the scene (0: across the "
         "whole scene)"},
        {"guidedEmission", ParamType::Bool, 1, 0, 1,
         "a directional light's cells send photons in proportion to what a pilot trace stored from them, with the "
         "power scaled to stay unbiased (0: every cell alike)"},
        {"causticRoughness", ParamType::Float, 0.35, 0.0, 1.0,
         "photons whose every bounce drew a lobe this smooth or smoother are caustic photons, read at the pixels "
         "(0: no caustic map; the final gather then sees the lights in near-specular surfaces)"},
        {"causticRadius", ParamType::Float, 0.01, 1e-5, 1.0, "the caustic map's estimate radius, per scene size"},
        choiceParam("photonOrder", {"kd", "hilbert"}, 0,
                    "the photon tree's nodes: kd-tree cells, each split at its photons' median along its longest "
                    "side (the paper's; ordered on the CPU), or ranges of the Hilbert curve at equal counts"),
        {"leafPhotons", ParamType::Int, 1, 1, 1024,
         "photons per leaf of the photon tree, at most (the paper's kd-tree: 1)"},
        {"cutLevel", ParamType::Int, 12, 0, 24,
         "E_min is the mean Eq. 3 estimate of this level of the photon tree and the next (the paper: 12-13)"},
        {"cutIterations", ParamType::Int, 4, 0, 8, "refinement iterations of the illumination cut (the paper: 3-5)"},
        {"cutThreshold", ParamType::Float, 1.2, 0.0, 100.0,
         "a cut node is refined when |E_p - E~_p| > this x E~_p (the paper: Delta E = 1.2 E~_p)"},
        {"cutGrid", ParamType::Int, IlluminationCut::kMaxGridCells, 0, IlluminationCut::kMaxGridCells,
         "cells of the uniform grid that lists, per cell, the cut nodes whose kernels reach into it, for Eq. 4's "
         "lookups (the same sum as the walk, faster on SIMD renderers; 0: the paper's walk of the tree above the "
         "cut)"},
        {"densityPhotons", ParamType::Int, 32, 1, 256, "k of the k-nearest-photon density estimates"},
        {"clusters", ParamType::Int, 1600, 1, 1048576, "shading clusters K (the paper: 1000-6000)"},
        {"alpha", ParamType::Float, 0.3, 0.0, 100.0,
         "Eq. 2's weight of position against normal, per scene size (the paper: 0.1-0.5)"},
        {"kmeansIterations", ParamType::Int, 4, 0, 64, "k-means iterations after seeding, at most"},
        {"kmeansTolerance", ParamType::Float, 0.002, 0.0, 1.0,
         "k-means has converged when an iteration moves at most this fraction of the pixels to another cluster "
         "(0: none)"},
        {"temporal", ParamType::Bool, 1, 0, 1, "reuse the previous frame's clusters (section 3.2)"},
        {"gatherRays", ParamType::Int, 256, 1, 65536, "final-gather rays per cluster sample (the paper: 250-500)"},
        {"glossyRays", ParamType::Int, 4, 0, 1024,
         "rays per pixel with a glossy lobe and frame for the glossy last bounce, drawn from the lobe (0: the "
         "interpolated irradiance reflected with the lobe's directional albedo)"},
        {"interpolationError", ParamType::Float, 0.2, 0.0, 10.0,
         "samples whose error 1/w is below this take part in a pixel's interpolation"},
        choiceParam("gatherAt", {"clusters", "pixels"}, 0,
                    "gather at the clusters' samples and interpolate (the paper), or at every pixel (Fig. 6)"),
        choiceParam("density", {"cut", "photons"}, 0,
                    "gather hits read the illumination cut (the paper), or the full photon map (Fig. 6)"),
        choiceParam("interpolation", {"auto", "fragments", "compute"}, 0,
                    "the interpolation pass's form: a full-screen triangle or one compute invocation per pixel; "
                    "auto: the faster form by this renderer's `bounce probe` ceilings, else fragments on a software "
                    "rasteriser and compute on a GPU, whose graphics units may be few"),
    };
    // Every pass with a small photon map, few clusters and short gathers: the tests' cheap settings.
    info.quickSets = {"photons=4096", "clusters=64", "gatherRays=16"};
    info.create = [](Frame& frame, const ParamValues& v) -> std::unique_ptr<Technique> {
        PhotonSettings s;
        s.tracer.photons = v.getInt("photons");
        s.tracer.maxBounces = v.getInt("maxBounces");
        s.tracer.russianRoulette = v.getBool("russianRoulette");
        const std::string first = v.getChoice(photonTechniqueInfo().params, "firstSurfaceRoulette");
        s.tracer.firstSurfaceRoulette = first == "auto"  ? kRouletteExceptDirectional
                                        : first == "all" ? kRouletteEveryLight
                                                         : 0u;
        s.tracer.projectionMap = v.getBool("projectionMap");
        s.tracer.guidedEmission = v.getBool("guidedEmission");
        s.tracer.causticRoughness = float(v.get("causticRoughness"));
        s.causticRadius = float(v.get("causticRadius"));
        s.tracer.kdOrder = v.getChoice(photonTechniqueInfo().params, "photonOrder") == "kd";
        s.leafPhotons = v.getInt("leafPhotons");
        s.cut.eminLevel = v.getInt("cutLevel");
        s.cut.iterations = v.getInt("cutIterations");
        s.cut.threshold = float(v.get("cutThreshold"));
        s.cut.densityPhotons = v.getInt("densityPhotons");
        s.cutGridCells = v.getInt("cutGrid");
        s.gather.cutGrid = s.cutGridCells > 0;
        s.clusters.clusters = v.getInt("clusters");
        s.clusters.alpha = float(v.get("alpha"));
        s.clusters.iterations = v.getInt("kmeansIterations");
        s.clusters.tolerance = float(v.get("kmeansTolerance"));
        s.clusters.temporal = v.getBool("temporal");
        s.clusters.everyPixel = v.getChoice(photonTechniqueInfo().params, "gatherAt") == "pixels";
        s.gather.rays = v.getInt("gatherRays");
        s.gather.fullPhotonMap = v.getChoice(photonTechniqueInfo().params, "density") == "photons";
        s.gather.densityPhotons = v.getInt("densityPhotons");
        s.gather.glossyRays = v.getInt("glossyRays");
        s.interpolationError = float(v.get("interpolationError"));
        const std::string form = v.getChoice(photonTechniqueInfo().params, "interpolation");
        s.interpolateAsCompute = form == "auto" ? Interpolation::defaultAsCompute() : form == "compute";
        return std::make_unique<Photon>(frame, s);
    };
    return info;
}

} // namespace bounce::gl
