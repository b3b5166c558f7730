#include "gl/technique/grb/grb_technique.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "gl/gl.h"
#include "gl/technique/grb/bundle_directions.h"
#include "gl/technique/grb/grb_atlas.h"
#include "gl/technique/grb/grb_display.h"
#include "gl/technique/grb/kbuffer.h"
#include "gl/technique/grb/radiance_atlases.h"

namespace bounce::gl {

namespace {

// The depth complexity k=auto measures: over this many directions of the sequence, at the k-buffer's
// own resolution (the issue measured 64 with Embree; 16 find the Cornell variants' largest).
constexpr int kDepthComplexityDirections = 16;
constexpr int kMaxAutoK = 64;

struct GrbChoice {
    KBufferSettings kbuffer;
    std::string reason;
    const StencilProbe* probe = nullptr;
    DepthComplexity depth;
};

// kbuffer=auto: stencil routing where the start-up probe finds it exact, else the atomic capture.
GrbChoice chooseCapture(const std::string& name, int samples)
{
    GrbChoice c;
    c.kbuffer.samples = samples;
    if (name == "atomic") {
        c.kbuffer.capture = KBufferCapture::Atomic;
        c.reason = "kbuffer=atomic";
    } else if (name == "peel") {
        c.kbuffer.capture = KBufferCapture::Peel;
        c.reason = "kbuffer=peel";
    } else {
        c.probe = &stencilProbe(samples);
        c.kbuffer.multisample = c.probe->multisample;
        if (name == "stencil") {
            c.kbuffer.capture = KBufferCapture::Stencil;
            c.reason = "kbuffer=stencil (" + c.probe->reason + ")";
        } else {
            c.kbuffer.capture = c.probe->exact ? KBufferCapture::Stencil : KBufferCapture::Atomic;
            c.reason = "kbuffer=auto: " + c.probe->reason + (c.probe->exact ? ": stencil" : ": atomic");
        }
    }
    return c;
}

core::AtlasSettings atlasSettings(const core::Scene& scene, const ParamValues& v)
{
    core::AtlasSettings s;
    s.texelsPerMetre =
        v.isAuto("density") ? core::texelsPerMetreFor(scene, v.get("atlasTexels")) : float(v.get("density"));
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    s.maxSize = std::max(1, int(maxSize));
    return s;
}

class GlobalRayBundles final : public Technique {
public:
    GlobalRayBundles(Frame& frame, const ParamValues& v)
        : directionsPerFrame_(v.getInt("directionsPerFrame")),
          choice_(chooseCapture(v.getChoice(grbTechniqueInfo().params, "kbuffer"), v.getInt("samples"))),
          atlas_(frame.scene(), atlasSettings(frame.scene(), v))
    {
        PassTimers setup;
        atlas_.fill(frame, setup);
        choice_.kbuffer.size = v.getInt("kbufferSize");
        if (v.isAuto("k")) {
            choice_.depth =
                // Depth complexity hardly depends on the resolution: measured at 128^2 at most.
                measureDepthComplexity(frame, atlas_, std::min(choice_.kbuffer.size, 128), kDepthComplexityDirections,
                                       setup);
            choice_.kbuffer.k = std::clamp(choice_.depth.largest, 1, kMaxAutoK);
        } else {
            choice_.kbuffer.k = v.getInt("k");
        }
        setup.endFrame(false);
        choice_.kbuffer.alphaMask = frame.gpuScene().hasAlphaMask();
        kbuffer_ = std::make_unique<KBuffer>(choice_.kbuffer);
        RadianceSettings rs;
        rs.glossy = frame.scene().hasGlossy();
        rs.punctual = frame.gpuScene().punctualLightCount() > 0;
        rs.interleaved = v.getBool("interleaved");
        // Every light the scene has that is not punctual is a triangle of an emitting mesh.
        const bool areaLights = int(frame.gpuScene().lights().size()) > frame.gpuScene().punctualLightCount();
        rs.areaGlossy = rs.glossy && areaLights;
        radiance_ = std::make_unique<RadianceAtlases>(atlas_, *kbuffer_, rs);
        const std::string fg = v.getChoice(grbTechniqueInfo().params, "finalGlossy");
        const bool finalGlossy = fg == "on" || (fg == "auto" && rs.glossy);
        emittersShown_ = v.getChoice(grbTechniqueInfo().params, "emitters") == "bundles" && areaLights;
        display_ = std::make_unique<GrbDisplay>(frame, *radiance_, *kbuffer_, finalGlossy, emittersShown_);
        stats_ = std::make_unique<KBufferStats>(*kbuffer_);
    }

    void render(Frame& frame, PassTimers& timers) override
    {
        if (!started_ || changed(frame)) startOver(frame, timers);
        const core::Bounds bounds = frame.gpuScene().bounds();
        for (int d = 0; d < directionsPerFrame_; ++d) {
            const std::uint64_t i = std::uint64_t(directions_);
            const BundleView view = bundleView(bounds, bundleDirection(i), bundleJitter(i), kbuffer_->size());
            kbuffer_->capture(frame, atlas_, view, timers);
            stats_->count(*kbuffer_, view, timers);
            // The final glossy bounce reads the same senders as this direction's transfer (before the swap).
            display_->gatherFinalGlossy(frame, atlas_, *radiance_, *kbuffer_, view, timers);
            radiance_->transfer(frame, atlas_, *kbuffer_, view, bundleDirection(i + 1), timers);
            ++directions_;
        }
        display_->display(frame, atlas_, *radiance_, timers);
        const KBufferStats::Totals t = stats_->read();
        frameOverflow_ = double(t.overflowPixels);
        overflowTotal_ += double(t.overflowPixels);
        largestSeen_ = std::max(largestSeen_, double(t.largestCount));
        occupied_ += double(t.occupiedPixels);
        entries_ += double(t.entries);
    }

    void restart() override { started_ = false; }
    bool carriesEmittersLight() const override { return emittersShown_; }
    // The glossy transfer samples the emitters through their cubes (AREA_GLOSSY); nothing else of grb's does.
    bool readsAreaShadowMaps() const override { return radiance_->settings().areaGlossy; }
    // The display is one atlas lookup per pixel, the directions' passes do not depend on the camera: at 1/4
    // of 256x256 on cornell-area a frame took 54.1 ms against 53.2 at full resolution (the display's 2.2 ms
    // became 0.7 plus 1.3 of upsampling and 0.4 of coarse G-buffer; README). Only the final glossy bounce,
    // gathered at every glossy pixel for every direction, gets cheaper at a coarser scale.
    bool indirectScales() const override { return display_->finalGlossy(); }
    int accumulatedSteps() const override { return directions_; }

    std::vector<Counter> counters() const override
    {
        const KBuffer& kb = *kbuffer_;
        const core::Atlas& a = atlas_.layout();
        std::vector<Counter> c = {
            {"directions", double(directions_)},
            {"directionsPerFrame", double(directionsPerFrame_)},
            {"k", double(kb.k())},
            {"kbufferSize", double(kb.size())},
            {"capture.stencil", kb.capture() == KBufferCapture::Stencil ? 1.0 : 0.0},
            {"capture.atomic", kb.capture() == KBufferCapture::Atomic ? 1.0 : 0.0},
            {"capture.peel", kb.capture() == KBufferCapture::Peel ? 1.0 : 0.0},
            {"kbufferEntriesPerDirection", double(kb.size()) * double(kb.size()) * double(kb.k())},
            {"overflowPixels", frameOverflow_},
            {"overflowPixelsPerDirection", frameOverflow_ / double(std::max(directionsPerFrame_, 1))},
            {"overflowPixelsTotal", overflowTotal_},
            {"depthComplexityLargestSeen", largestSeen_},
            {"hitsPerOccupiedPixel", occupied_ > 0.0 ? entries_ / occupied_ : 0.0},
            {"atlasWidth", double(a.width)},
            {"atlasHeight", double(a.height)},
            {"atlasCharts", double(a.charts.size())},
            {"atlasTexelsFilled", double(atlas_.filledTexels())},
            {"texelsPerMetre", double(a.texelsPerMetre)},
            {"finalGlossy", display_->finalGlossy() ? 1.0 : 0.0},
        };
        if (kb.capture() == KBufferCapture::Stencil) {
            c.push_back({"stencilSamples", double(kb.samples())});
            c.push_back({"stencilSlices", double(kb.slices())});
            c.push_back({"stencilMultisample", kb.settings().multisample ? 1.0 : 0.0});
        }
        if (choice_.probe) {
            c.push_back({"stencilProbeExact", choice_.probe->exact ? 1.0 : 0.0});
            c.push_back({"stencilProbeMismatchedPixels", double(choice_.probe->mismatchedPixels)});
            c.push_back({"stencilProbePixels", double(choice_.probe->pixels)});
        }
        if (choice_.depth.directions > 0) {
            c.push_back({"depthComplexityMeasured", double(choice_.depth.largest)});
            c.push_back({"depthComplexityMeanOccupied", choice_.depth.meanOccupied});
        }
        return c;
    }

    nlohmann::json notes() const override
    {
        return {{"capture", kbufferCaptureName(kbuffer_->capture())},
                {"captureReason", choice_.reason},
                {"kReason", choice_.depth.directions > 0 ? "k=auto: the largest depth complexity over " +
                                                               std::to_string(choice_.depth.directions) +
                                                               " directions, " + std::to_string(choice_.depth.largest)
                                                         : "k=" + std::to_string(kbuffer_->k())}};
    }

private:
    int directionsPerFrame_;
    GrbChoice choice_;
    GrbAtlas atlas_;
    std::unique_ptr<KBuffer> kbuffer_;
    std::unique_ptr<RadianceAtlases> radiance_;
    std::unique_ptr<GrbDisplay> display_;
    std::unique_ptr<KBufferStats> stats_;
    bool started_ = false;
    bool emittersShown_ = false; // emitters=bundles in a scene with emitting triangles
    FrameVersion version_;
    int directions_ = 0;
    double frameOverflow_ = 0.0, overflowTotal_ = 0.0, largestSeen_ = 0.0, occupied_ = 0.0, entries_ = 0.0;

    // The scene or a light moved; the camera only matters to the final glossy bounce.
    bool changed(const Frame& frame) const
    {
        const FrameVersion& v = frame.version();
        return v.scene != version_.scene || v.lights != version_.lights ||
               (display_->finalGlossy() && v.camera != version_.camera);
    }

    void startOver(Frame& frame, PassTimers& timers)
    {
        radiance_->clear();
        radiance_->seed(frame, atlas_, timers);
        display_->clear();
        directions_ = 0;
        overflowTotal_ = largestSeen_ = occupied_ = entries_ = 0.0;
        version_ = frame.version();
        started_ = true;
    }
};

} // namespace

TechniqueInfo grbTechniqueInfo()
{
    TechniqueInfo info;
    info.name = "grb";
    info.paper = "Hermes, Henrich, Grosch & Mueller 2010";
    info.lightPaths = core::LightPaths::Full;
    info.summary = "global ray-bundles: a k-buffer per direction exchanges radiance between texture-atlas texels, "
                   "multi-bounce diffuse and glossy, progressive";
    info.progressive = true;
    info.passes = {
        {"capture", "the scene rasterised into the k-buffer along one direction (per direction)", ""},
        {"kbuffer-stats", "overflowed pixels and depth complexity of the k-buffer (per direction)", ""},
        {"transfer", "Eq. 3 over every atlas texel, sender/receiver atlases swap (per direction)", ""},
        {"display", "the atlas's indirect light (emitters=bundles: and the emitters' light) at every pixel", ""},
        {"seed", "punctual lights' direct light into the atlas through the shadow maps",
         "when accumulation starts over and the scene has point, spot or directional lights"},
        {"final-glossy", "Eq. 3 towards the eye at glossy pixels (per direction, Sec. 5.3)",
         "finalGlossy on (auto: the scene has glossy materials)"},
    };
    info.reads = {GBufferChannel::Position, GBufferChannel::Normal, GBufferChannel::Diffuse, GBufferChannel::Specular};
    ParamDecl dirs{"directionsPerFrame",
                   ParamType::Int,
                   4,
                   1,
                   4096,
                   "bundle directions added per frame; time per frame is linear in it"};
    ParamDecl k{"k",
                ParamType::Int,
                kAutoValue,
                1,
                254,
                "entries per k-buffer pixel (auto: the measured depth complexity); fewer than the scene's depth "
                "complexity drops the samples of the overflowing pixels"};
    k.allowAuto = true;
    ParamDecl size{
        "kbufferSize", ParamType::Int,
        256,           8,
        4096,          "k-buffer pixels per side over the bounding sphere; finer bundles cost more per direction"};
    ParamDecl samples{"samples", ParamType::Int,
                      8,         1,
                      32,        "stencil routing: samples per slice (the paper's 8; at most the driver's)"};
    samples.powerOfTwo = true;
    ParamDecl density{"density",
                      ParamType::Float,
                      kAutoValue,
                      1e-3,
                      1e6,
                      "atlas texels per metre (auto: from atlasTexels and the surface area); accuracy and cost grow "
                      "with its square"};
    density.allowAuto = true;
    ParamDecl texels{"atlasTexels", ParamType::Int,
                     32768,         64,
                     1 << 26,       "texels the surfaces cover when density is auto (the paper: 2048^2 atlases)"};
    ParamDecl interleaved{"interleaved",
                          ParamType::Bool,
                          1,
                          0,
                          1,
                          "Sec. 5.5 interleaved bounces; off: one bounce (senders send only direct light)"};
    info.params = {
        dirs,
        choiceParam("kbuffer", {"auto", "stencil", "atomic", "peel"}, 0,
                    "capture: stencil routing (the paper), image atomics, depth peeling (reference); auto: "
                    "stencil where a start-up probe finds it exact, else atomic"),
        k, size, samples, density, texels, interleaved,
        choiceParam("finalGlossy", {"auto", "on", "off"}, 0,
                    "Sec. 5.3 final glossy bounce towards the eye (auto: where the scene is glossy); restarts "
                    "on camera moves"),
        // The default by measurement (issue 58, README "emitters"): after 256 directions the frame's direct
        // light is closer to the path tracer on every Cornell variant with an emitter, and the same without.
        choiceParam("emitters", {"bundles", "frame"}, 1,
                    "light from emitting surfaces as seen: bundles (Sec. 5.1: the bundles' direct atlas, and the "
                    "final glossy bounce its glossy reflection; with finalGlossy off glossy surfaces show none) "
                    "or frame (the frame's direct light, as the paper's Sec. 6.5 takes for a few simple "
                    "emitters; the bundles still carry it to the first bounce)")};
    // Every pass with fewer, coarser bundles and a small atlas: the tests' cheap settings.
    info.quickSets = {"directionsPerFrame=2", "kbufferSize=64", "atlasTexels=4096"};
    info.create = [](Frame& frame, const ParamValues& v) -> std::unique_ptr<Technique> {
        try {
            return std::make_unique<GlobalRayBundles>(frame, v);
        } catch (const core::AtlasError& e) {
            throw std::invalid_argument(std::string("grb: ") + e.what());
        }
    };
    return info;
}

} // namespace bounce::gl
