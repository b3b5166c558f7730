#include "gl/technique/pointproj/pointproj_technique.h"

#include <algorithm>
#include <memory>
#include <string>

#include "gl/frame/points/adaptive_pixels.h"
#include "gl/frame/points/point_cloud.h"
#include "gl/technique/pointproj/projection_gather.h"

namespace bounce::gl {

namespace {

struct PointprojSettings {
    int points = 65536;
    ProjectionSettings projection;
    AdaptiveSettings adaptive;
    bool progressive = true;
    int bounces = 1;
    int bounceNodes = 4096;
};

AdaptiveSettings inScene(AdaptiveSettings a, bool glossyScene)
{
    a.glossyScene = glossyScene;
    return a;
}

class Pointproj final : public Technique {
public:
    Pointproj(Frame& frame, const PointprojSettings& s)
        : settings_(s),
          cloud_(frame, std::size_t(s.points), 1, s.bounces > 1),
          gather_(frame, cloud_, s.projection, s.bounces > 1),
          pixels_(frame, inScene(s.adaptive, cloud_.glossy()))
    {
        stride_ = std::max(1, cloud_.count() / std::clamp(s.bounceNodes, 1, cloud_.count()));
        if (s.bounces > 1) gathered_ = Buffer("pointproj.bounceGathered", std::size_t(cloud_.count() / stride_) * 16);
    }

    void render(Frame& frame, PassTimers& timers) override
    {
        cloud_.update(frame, timers);
        if (frame.version().scene != orderedScene_) {
            // "Upon manipulation ... we re-cluster the points" (§4 "Scene Manipulation"): where the geometry
            // moved, the clusters are cut again where the points are now, on the GPU as the paper does it
            // (pass "recluster"). The hole rays' BVH is the frame's, which follows the moved scene.
            cloud_.reorder(frame, timers);
            ++reclusters_;
            orderedScene_ = frame.version().scene;
        }
        if (!(frame.version() == version_)) {
            version_ = frame.version();
            steps_ = 0;
        }
        const auto seed = std::uint32_t(settings_.progressive ? steps_ : 0);
        cloud_.light(frame, timers);
        for (int b = 1; b < settings_.bounces; ++b) {
            gather_.gatherPoints(frame, cloud_, stride_, gathered_, seed * 7919u + std::uint32_t(b), timers);
            cloud_.relight(gathered_, stride_, timers);
        }
        gather_.clearStats();
        for (int level = 0; level < pixels_.levels(); ++level) {
            const int n = pixels_.select(frame, level, timers);
            gather_.gatherPixels(frame, pixels_, n, cloud_, seed, timers);
            pixels_.interpolate(frame, level, timers);
        }
        ++steps_;
        pixels_.compose(frame, settings_.progressive ? 1.0f / float(steps_) : 1.0f, timers);
        stats_ = gather_.stats();
    }

    // The points, and the hole rays' hits, are lit by pointLightDefines' programs alone.
    bool readsShadowMaps(const Frame& frame) const override { return pointLightReadsShadowMaps(frame); }

    void setUniforms(const ParamValues& values) override
    {
        pixels_.setThresholds(float(values.get("epsilon")), float(values.get("lambda")));
        restart(); // the running mean belongs to the old thresholds
    }

    void restart() override { steps_ = 0; }
    int accumulatedSteps() const override { return steps_; }

    std::vector<Counter> counters() const override
    {
        const double targets = std::max<double>(stats_.targets, 1.0);
        return {
            {"points", double(cloud_.count())},
            {"clusters", double(settings_.projection.clusters)},
            {"gatherPixels", double(stats_.targets)},
            {"pointsProjectedPerPixel", double(stats_.projected) / targets},
            {"emptyTexelsPerPixel", double(stats_.emptyTexels) / targets},
            {"filledTexelsPerPixel", double(stats_.filledTexels) / targets},
            {"holeRaysPerPixel", double(stats_.holeRays) / targets},
            {"holeHitsPerPixel", double(stats_.holeHits) / targets},
            {"uniformFallbacks", double(stats_.uniformFallbacks)},
            {"clampedSplats", double(stats_.clampedSplats)},
            {"accumulatedFrames", double(steps_)},
            {"reclusters", double(reclusters_)},
            {"postFilterWidth", pixels_.postFilterRadius() > 0 ? 2.0 * pixels_.postFilterRadius() + 1.0 : 0.0},
        };
    }

private:
    PointprojSettings settings_;
    PointCloud cloud_;
    ProjectionGather gather_;
    AdaptivePixels pixels_;
    Buffer gathered_;
    int stride_ = 1;
    int steps_ = 0;
    int reclusters_ = 0;
    // The cloud is ordered as the scene was loaded (version().scene 0); re-clustered when that changes.
    std::uint64_t orderedScene_ = 0;
    FrameVersion version_{~0ull, ~0ull, ~0ull};
    ProjectionStats stats_;
};

} // namespace

TechniqueInfo pointprojTechniqueInfo()
{
    TechniqueInfo info;
    info.name = "pointproj";
    info.paper = "Maletz, Wang & Bowers 2011";
    info.lightPaths = core::LightPaths::OneBounce;
    info.progressive = true;
    info.summary = "final gathering by importance-sampled, clustered point splats into hemi-octahedral micro-buffers, "
                   "with image-space adaptive sampling";
    info.passes = {
        {"point-update", "surface points from (triangle, barycentrics) on the scene as it is", ""},
        {"point-light",
         "direct light at every point: a shadow ray per light, or the shadow maps with emitting triangles; half floats",
         ""},
        {"recluster",
         "§4's re-clustering on the GPU: the points sorted along x, y and z, then a median partition per level",
         "the scene's geometry moved"},
        {"bounce-gather", "point projection at every stride-th point", "bounces > 1"},
        {"relight", "the points' radiance: direct + the gathered bounce", "bounces > 1"},
        {"adaptive-select", "the pixels to gather at: the 4x4 grid, then where the coherence metric exceeds epsilon",
         ""},
        {"gather", "one micro-buffer per pixel: importance, carry allocation, splats, BRDF", ""},
        {"interpolate", "joint bilateral interpolation of the pixels not gathered", ""},
        {"compose",
         "§4's joint bilateral post-filter (7x7 at 512x512, 3x3 in glossy scenes), diffuse colour x "
         "diffuse part + glossy part, the progressive mean",
         ""},
    };
    info.reads = {GBufferChannel::Position, GBufferChannel::Normal, GBufferChannel::Diffuse, GBufferChannel::Specular};
    info.params = {
        {"points", ParamType::Int, 65536, 1024, 8388608, "surface points (a power of two; the paper: 256K)", true},
        {"clusters", ParamType::Int, 512, 16, 4096, "equal kd-tree clusters of the points (§3.2: 512, 9 levels)", true},
        {"samples", ParamType::Int, 2048, 0, 65536, "N_s, importance samples per pixel (§4: 4 x 512)"},
        {"randomPerCluster", ParamType::Int, 2, 1, 16, "N_rnd, random points per cluster for its importance (§3.2: 2)"},
        choiceParam(
            "projection", {"importance", "uniform", "all"}, 0,
            "which points are projected: by importance, uniformly (Fig. 9's random), or every point (brute force)"),
        choiceParam("splat", {"adaptive", "1", "2", "3"}, 0,
                    "splat size: Eq. 5's adaptive size, or fixed texels (Fig. 7)"),
        choiceParam("splatShare", {"drawn", "expected"}, 0,
                    "the share of its cluster a splat stands for: 1 / (N_rnd + n_k), the points drawn from it, or the "
                    "paper's 1 / (N_s p_k)"),
        {"holeFill", ParamType::Int, 4, 0, 16,
         "passes of the micro-buffer's hole fill (an empty texel with most neighbours covered takes the farthest); "
         "0: none, as the paper"},
        {"holeRays", ParamType::Bool, 1, 0, 1,
         "a texel still empty casts a ray: where it meets the scene, the hit's direct light; where not, open space; "
         "0: none, as the paper"},
        {"adaptive", ParamType::Bool, 1, 0, 1, "image-space adaptive sampling (§3.3); 0: gather at every pixel"},
        {"epsilon", ParamType::Float, 0.3, 0, 100, "the coherence threshold of the first refinement, doubled per level",
         false, ParamUpdate::Uniform},
        {"lambda", ParamType::Float, 8, 0, 1000, "the weight of the radiance term of the coherence metric", false,
         ParamUpdate::Uniform},
        choiceParam(
            "postFilter", {"auto", "7x7", "3x3", "off"}, 0,
            "§4's post-process joint bilateral filter of the indirect light; auto: 7x7 (3x3 in a scene "
            "with a glossy material) at 512x512, scaled with the image's smaller side (none below 171 pixels, or "
            "512 in a glossy scene)"),
        {"progressive", ParamType::Bool, 1, 0, 1,
         "each frame draws new random points and is averaged in, until something moves"},
        {"bounces", ParamType::Int, 1, 1, 8, "indirect bounces; > 1 gathers at the points first (§4)"},
        {"bounceNodes", ParamType::Int, 4096, 64, 1048576,
         "gather locations of each extra bounce: one per run of points / this many", true},
    };
    // Every pass with a small cloud and fewer samples per pixel: the tests' cheap settings.
    info.quickSets = {"points=4096", "clusters=64", "samples=256"};
    info.create = [](Frame& frame, const ParamValues& v) -> std::unique_ptr<Technique> {
        const std::vector<ParamDecl>& decls = pointprojTechniqueInfo().params;
        PointprojSettings s;
        s.points = v.getInt("points");
        s.projection.clusters = v.getInt("clusters");
        s.projection.samples = v.getInt("samples");
        s.projection.randomPerCluster = v.getInt("randomPerCluster");
        const std::string mode = v.getChoice(decls, "projection");
        s.projection.mode = mode == "uniform" ? ProjectionSettings::Mode::Uniform
                            : mode == "all"   ? ProjectionSettings::Mode::All
                                              : ProjectionSettings::Mode::Importance;
        const std::string splat = v.getChoice(decls, "splat");
        s.projection.fixedSplat = splat == "adaptive" ? 0 : std::stoi(splat);
        s.projection.shareDrawn = v.getChoice(decls, "splatShare") == "drawn";
        s.projection.holeFill = v.getInt("holeFill");
        s.projection.holeRays = v.getInt("holeRays") != 0;
        s.adaptive.adaptive = v.getBool("adaptive");
        s.adaptive.epsilon = float(v.get("epsilon"));
        s.adaptive.lambda = float(v.get("lambda"));
        s.progressive = v.getBool("progressive");
        s.bounces = v.getInt("bounces");
        s.bounceNodes = v.getInt("bounceNodes");
        const std::string filter = v.getChoice(decls, "postFilter");
        s.adaptive.postFilter = filter == "7x7" ? 3 : filter == "3x3" ? 1 : filter == "off" ? 0 : -1;
        return std::make_unique<Pointproj>(frame, s);
    };
    return info;
}

} // namespace bounce::gl
