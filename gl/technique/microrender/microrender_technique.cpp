#include "gl/technique/microrender/microrender_technique.h"

#include <algorithm>
#include <memory>
#include <string>

#include "gl/context/context.h"
#include "gl/frame/multires.h"
#include "gl/frame/points/pixel_gather.h"
#include "gl/frame/points/point_cloud.h"
#include "gl/frame/ray_caster.h"
#include "gl/technique/microrender/micro_gather.h"
#include "gl/technique/microrender/point_hierarchy.h"

namespace bounce::gl {

namespace {

struct MicrorenderSettings {
    int points = 65536;
    MicroGatherSettings gather;
    int bounces = 1;
    int bounceNodes = 4096;
    MultiresSettings multires;
};

class Microrender final : public Technique {
public:
    Microrender(Frame& frame, const MicrorenderSettings& s)
        : settings_(s),
          cloud_(frame, std::size_t(s.points), 1, s.bounces > 1),
          hierarchy_(cloud_),
          gather_(frame, s.gather, hierarchy_, s.bounces > 1),
          targets_(frame, s.multires)
    {
        // §4: "gathering incident illumination at the hierarchy level 12 (4 k nodes)": one representative
        // point per node of the level with bounceNodes nodes.
        stride_ = std::max(1, cloud_.count() / std::clamp(s.bounceNodes, 1, cloud_.count()));
        if (s.bounces > 1) gathered_ = Buffer("microrender.bounceGathered", std::size_t(cloud_.count() / stride_) * 16);
    }

    void render(Frame& frame, PassTimers& timers) override
    {
        cloud_.update(frame, timers);
        const RayCaster& caster = frame.rayCaster(); // the BVH of the geometry as it is now
        cloud_.light(frame, timers);
        hierarchy_.build(cloud_, timers);
        for (int b = 1; b < settings_.bounces; ++b) {
            gather_.gatherPoints(frame, cloud_, hierarchy_, caster, stride_, gathered_, timers);
            cloud_.relight(gathered_, stride_, timers);
            hierarchy_.build(cloud_, timers);
        }
        targets_.select(frame, timers);
        gather_.gatherPixels(frame, targets_, cloud_, hierarchy_, caster, timers);
        targets_.upsample(frame, timers);
    }

    // The points, and the hits of the ray-cast micro-pixels, are lit by pointLightDefines' programs alone.
    bool readsShadowMaps(const Frame& frame) const override { return pointLightReadsShadowMaps(frame); }

    void setUniforms(const ParamValues& values) override
    {
        targets_.setThresholds(float(values.get("depthThreshold")), float(values.get("normalThreshold")));
        gather_.setCut(float(values.get("cut")));
    }

    std::vector<Counter> counters() const override
    {
        const MicroStats& s = gather_.stats();
        const double samples = std::max<double>(s.samples, 1.0);
        return {
            {"points", double(cloud_.count())},
            {"nodes", double(2 * hierarchy_.leafCount() - 1)},
            {"gatherSamples", double(s.samples)},
            {"microBuffersWithRays", double(s.withList)},
            {"rayCastShare", double(s.withList) / samples},
            {"listOverflows", double(s.listOverflows)},
            {"emptyMicroPixels", double(s.emptyPixels)},
            {"nodesVisitedPerSample", double(s.visited) / samples},
            {"nodesRasterisedPerSample", double(s.rasterised) / samples},
            {"rays", double(s.rays)},
            {"rayPixels", double(s.rayPixels)},
        };
    }

private:
    MicrorenderSettings settings_;
    PointCloud cloud_;
    PointHierarchy hierarchy_;
    MicroGather gather_;
    PixelGather targets_;
    Buffer gathered_;
    int stride_ = 1;
};

} // namespace

TechniqueInfo microrenderTechniqueInfo()
{
    TechniqueInfo info;
    info.name = "microrender";
    info.paper = "Ritschel, Engelhardt, Grosch, Seidel, Kautz & Dachsbacher 2009";
    info.lightPaths = core::LightPaths::OneBounce;
    info.summary = "final gathering by rasterising a point hierarchy into importance-warped micro-buffers, ray casting "
                   "the leaves too large for a micro-pixel";
    info.passes = {
        {"point-update", "surface points from (triangle, barycentrics) on the scene as it is", ""},
        {"point-light",
         "direct light at every point: a shadow ray per light, or the shadow maps with emitting triangles; half floats",
         ""},
        {"hierarchy", "the point hierarchy rebuilt bottom-up: spheres, normal cones, radiance", ""},
        {"bounce-gather", "micro-rendering at the representatives of one hierarchy level", "bounces > 1"},
        {"relight", "the points' radiance: direct + the gathered bounce", "bounces > 1"},
        {"minmax-mipmap", "eye-space min-max pyramid choosing the gather locations", ""},
        {"gather-select", "the gather locations listed", ""},
        {"gather", "one micro-buffer per gather location: cut, rasterise, ray cast, convolve", ""},
        {"upsample", "joint bilateral upsampling to every pixel", ""},
    };
    info.reads = {GBufferChannel::Position, GBufferChannel::Normal, GBufferChannel::Diffuse, GBufferChannel::Specular};
    info.params = {
        {"points", ParamType::Int, 65536, 256, 8388608,
         "surface points, the hierarchy's leaves (a power of two; the paper: about 1M)", true},
        choiceParam("microBuffer", {"8", "16", "24"}, 2, "micro-buffer side in pixels (Fig. 12)"),
        {"warp", ParamType::Bool, 1, 0, 1, "importance warping by the BRDF (§2.3); 0: the cosine (Nusselt) mapping"},
        {"rayCast", ParamType::Bool, 1, 0, 1,
         "ray cast the leaves larger than a micro-pixel and the holes (§2.2); 0: rasterise them as points (Fig. 11)"},
        {"cut", ParamType::Float, 1.0, 0.05, 64,
         "a node is rasterised when its solid angle is at most this x the micro-pixel's (§2.2: 1); larger: coarser "
         "cut, holes ray cast",
         false, ParamUpdate::Uniform},
        {"bounces", ParamType::Int, 1, 1, 8, "indirect bounces; > 1 gathers at the points first (§4)"},
        choiceParam("rays", {"triangles", "discs"}, 0,
                    "what the rays meet: triangles (the scene's BVH, every micro-pixel where the list holds leaves "
                    "and every hole, lit by the nearest listed leaf or the lights) or discs (§2.2: the listed "
                    "leaves' discs only, no ray where the list is empty: holes stay)"),
        choiceParam("silhouettes", {"coverage-depth", "coverage", "off"}, 0,
                    "with rays=triangles, a ray through every micro-pixel a silhouette crosses, its answer standing: "
                    "where the nodes rasterised into it do not fill it or lie at different depths (coverage-depth), "
                    "where they do not fill it (coverage); off: the paper's point rasterisation, which dilates "
                    "silhouettes by up to a micro-pixel"),
        choiceParam("cutWalk", {"auto", "subtrees", "levels"}, 0,
                    "the cut's walk (the same cut): each invocation one of 64 subtrees (the paper's one walk per "
                    "thread), or the group level by level from a shared queue (balanced); auto: subtrees on a "
                    "software rasteriser, levels on a GPU, whose warps wait for their longest walk"),
        {"cutQueue", ParamType::Int, 768, 64, 4096,
         "the walk by levels: nodes each of its two shared-memory queues holds (even); children that find it full "
         "are walked as subtrees"},
        {"stages", ParamType::Int, 4, 1, 4,
         "profiling: the gather kernel stops after stage 1 warp, 2 cut, 3 rays, 4 convolution (below 4: no light)"},
        {"bounceNodes", ParamType::Int, 4096, 64, 1048576,
         "gather locations of each extra bounce: one per node of the hierarchy level with this many nodes", true},
    };
    for (ParamDecl p : multiresParams()) {
        // Gathering at every 4th pixel in each direction by default (§2.4, the paper's previews: "1/16-th
        // image resolution"); 0: at every pixel.
        if (p.name == "coarsestLevel") {
            p.defaultValue = 2;
            p.meaning = "gather every 2^level pixels in each direction where the surface is smooth (Fig. 10: 0 every "
                        "pixel, 1 a quarter, 2 a sixteenth), finer at depth and normal edges";
        }
        info.params.push_back(p);
    }
    // Every pass with a small cloud and 8^2 micro-buffers: the tests' cheap settings.
    info.quickSets = {"points=4096", "microBuffer=8"};
    info.create = [](Frame& frame, const ParamValues& v) -> std::unique_ptr<Technique> {
        MicrorenderSettings s;
        s.points = v.getInt("points");
        s.gather.resolution = std::stoi(v.getChoice(microrenderTechniqueInfo().params, "microBuffer"));
        s.gather.warp = v.getBool("warp");
        s.gather.rayCast = v.getBool("rayCast");
        s.gather.rayDiscs = v.getChoice(microrenderTechniqueInfo().params, "rays") == "discs";
        const std::string silhouettes = v.getChoice(microrenderTechniqueInfo().params, "silhouettes");
        s.gather.silhouetteRays = silhouettes != "off";
        s.gather.silhouetteDepths = silhouettes == "coverage-depth";
        s.gather.cut = float(v.get("cut"));
        s.gather.stages = v.getInt("stages");
        const std::string walk = v.getChoice(microrenderTechniqueInfo().params, "cutWalk");
        s.gather.cutQueue = walk == "auto"     ? (softwareRasterizer() ? 0 : v.getInt("cutQueue"))
                            : walk == "levels" ? v.getInt("cutQueue")
                                               : 0;
        s.bounces = v.getInt("bounces");
        s.bounceNodes = v.getInt("bounceNodes");
        s.multires = multiresSettingsFrom(v);
        return std::make_unique<Microrender>(frame, s);
    };
    return info;
}

} // namespace bounce::gl
