// The stencil-based multiresolution gather (§3.2) and hierarchical image-space radiosity (§3.5) of
// gl/technique/isr/ (multires_gather, multires_technique, vpl_tree, hisr_technique): the layout of the
// flattened buffer, the coverage of every pixel by exactly one valid fragment, equality with the
// full-resolution gathers at zero thresholds, the VPL tree against a CPU rebuild from the same RSM, and
// odd viewports. Tiny images and RSMs: llvmpipe on two cores.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/image.h"
#include "core/metrics.h"
#include "gl/context/context.h"
#include "gl/frame/frame.h"
#include "gl/frame/multires.h"
#include "gl/frame/rsm.h"
#include "gl/probe/machine_probe.h"
#include "gl/renderer.h"
#include "gl/technique/isr/hisr_technique.h"
#include "gl/technique/isr/multires_gather.h"
#include "gl/technique/isr/vpl_gather.h"
#include "gl/technique/isr/vpl_sample.h"
#include "gl/technique/isr/vpl_tree.h"
#include "gl/technique/photon/final_gather.h"
#include "tests/gl/gl_test_fixture.h"
#include "tests/image_expect.h"

namespace bounce {
namespace {

using Sets = std::vector<std::pair<std::string, std::string>>;

struct Rendered {
    core::Image indirect;
    core::Image position; // w channel of the G-buffer in .r: 1 where geometry
    std::vector<gl::Counter> counters;
};

Rendered render(const core::Scene& scene, const std::string& technique, const Sets& sets, int w, int h)
{
    const gl::TechniqueInfo& info = gl::findTechnique(technique);
    gl::ParamValues frameValues(gl::frameParams()), values(info.params);
    frameValues.setValue("shadow.size", 256);
    for (const auto& [k, v] : sets) values.set(info.params, k, v);
    gl::Renderer r(scene, technique, frameValues, values, w, h);
    r.renderFrame();
    Rendered out{r.frame().read(r.frame().indirect()), core::Image(w, h), r.counters()};
    const std::vector<float> p = r.frame().readPositions();
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) out.position.set(x, h - 1 - y, glm::vec3(p[(std::size_t(y) * w + x) * 4 + 3]));
    return out;
}

double counter(const std::vector<gl::Counter>& cs, const std::string& name)
{
    for (const gl::Counter& c : cs)
        if (c.name == name) return c.value;
    ADD_FAILURE() << "no counter " << name;
    return 0.0;
}

int geometryPixels(const core::Image& position)
{
    int n = 0;
    for (int y = 0; y < position.height; ++y)
        for (int x = 0; x < position.width; ++x) n += position.at(x, y).x != 0.0f;
    return n;
}

void expectFinite(const core::Image& img, const std::string& what)
{
    std::size_t bad = 0;
    for (float v : img.rgb) bad += !std::isfinite(v);
    EXPECT_EQ(bad, 0u) << what << ": non-finite values";
}

// The VPL cache's layout (glsl/technique/isr/vpl.glsl) and the VPL tree's (vpl_tree.glsl).
struct GpuVpl {
    glm::vec4 positionArea, normal, flux;
};
struct Node {
    glm::vec4 positionArea, normal, flux, range;
};

// A frame of `scene` at w x h (256^2 shadow maps), begun, with its G-buffer rendered unless `gbuffer` is false.
std::unique_ptr<gl::Frame> testFrame(const core::Scene& scene, int w, int h, gl::PassTimers& timers,
                                     bool gbuffer = true)
{
    gl::FrameSettings fs;
    fs.width = w;
    fs.height = h;
    fs.shadowMapSize = 256;
    auto frame = std::make_unique<gl::Frame>(scene, fs);
    frame->beginFrame();
    if (gbuffer) frame->renderGBuffer(timers);
    return frame;
}

// A VPL cache in whole uniform blocks (vpl_gather.h) holding `vpls`.
gl::Buffer vplCache(const std::vector<GpuVpl>& vpls)
{
    gl::Buffer cache("test.vpls", gl::vplCacheBytes(int(vpls.size())));
    cache.update(0, vpls.size() * sizeof(GpuVpl), vpls.data());
    return cache;
}

class IsrMultiresTest : public GlTest {};

// ---------------------------------------------------------------------------------------------------
// Layout of the flattened buffer.

// Level l has ceil(w / 2^l) x ceil(h / 2^l) patches (so every pixel has a parent at every size), levels
// do not overlap, and the levels stop where one patch covers the image (1x1: level 0 only).
TEST(IsrMultiresLayout, LevelRectsForOddSizes)
{
    const std::vector<glm::ivec4> r = gl::multiresLevelRects(333, 200, 4);
    ASSERT_EQ(r.size(), 5u);
    EXPECT_EQ(r[0], glm::ivec4(0, 0, 333, 200));
    EXPECT_EQ(r[1], glm::ivec4(333, 0, 167, 100));
    EXPECT_EQ(r[2], glm::ivec4(333, 100, 84, 50));
    EXPECT_EQ(r[3], glm::ivec4(333, 150, 42, 25));
    EXPECT_EQ(r[4], glm::ivec4(333, 175, 21, 13));
    EXPECT_EQ(gl::multiresLevelRects(1, 1, 4).size(), 1u);
    EXPECT_EQ(gl::multiresLevelRects(3, 1, 4).size(), 3u); // 3 -> 2 -> 1 patches wide
    EXPECT_EQ(gl::multiresLevelRects(64, 64, 0).size(), 1u);
    for (const auto& [w, h] : {std::pair{333, 200}, std::pair{1, 7}, std::pair{5, 3}}) {
        const std::vector<glm::ivec4> rs = gl::multiresLevelRects(w, h, 15);
        for (std::size_t l = 1; l < rs.size(); ++l) {
            EXPECT_EQ(rs[l].z, (w + (1 << l) - 1) >> l);
            EXPECT_EQ(rs[l].w, (h + (1 << l) - 1) >> l);
            EXPECT_EQ(rs[l].x, w);
            EXPECT_EQ(rs[l].y, rs[l - 1].x == w ? rs[l - 1].y + rs[l - 1].w : 0);
        }
        EXPECT_EQ(rs.back().z * rs.back().w, 1) << "levels stop at one patch covering the image";
    }
}

// The automatic coarsest level keeps at least 64 patches across the longer side (the paper's 64 x 64
// coarsest buffer: 16 x 16 pixels at its 1024 x 1024).
TEST(IsrMultiresLayout, AutoCoarsestLevelKeepsSixtyFourPatchesAcross)
{
    EXPECT_EQ(gl::autoCoarsestLevel(1024, 1024), 4);
    EXPECT_EQ(gl::autoCoarsestLevel(512, 512), 3);
    EXPECT_EQ(gl::autoCoarsestLevel(333, 200), 2); // 84 patches across at level 2, 42 at level 3
    EXPECT_EQ(gl::autoCoarsestLevel(200, 333), 2);
    EXPECT_EQ(gl::autoCoarsestLevel(126, 126), 0);
    EXPECT_EQ(gl::autoCoarsestLevel(127, 127), 1); // 64 patches of 2 pixels, the last one pixel wide
    EXPECT_EQ(gl::autoCoarsestLevel(128, 1), 1);
    EXPECT_EQ(gl::autoCoarsestLevel(1, 1), 0);
}

// ---------------------------------------------------------------------------------------------------
// Coverage: each pixel with geometry lies in exactly one valid fragment.

// Runs MultiresGather over the cornell-spot G-buffer with a few arbitrary VPLs and checks, from the
// alpha of the flattened illumination buffer (>= 1 exactly at the fragments that passed the stencil test):
// every pixel with geometry has exactly one valid ancestor over the levels, background pixels at most one, and
// the per-level counts of the stencil pass equal the fragments the stenciled gather wrote.
void checkCoverage(int w, int h, const gl::MultiresSettings& settings, std::vector<int>* perLevelOut = nullptr)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    gl::PassTimers timers;
    const auto framePtr = testFrame(scene, w, h, timers);
    gl::Frame& frame = *framePtr;
    frame.clearIndirect();
    const std::vector<GpuVpl> vpls = {{{0.3f, 0.0f, 0.3f, 1e-3f}, {0, 1, 0, 0}, {0.01f, 0.01f, 0.01f, 0}},
                                      {{0.55f, 0.3f, 0.3f, 1e-3f}, {-1, 0, 0, 0}, {0.02f, 0.0f, 0.0f, 0}}};
    const gl::Buffer cache = vplCache(vpls);
    gl::MultiresGather gather(frame, settings);
    gather.run(frame, cache, int(vpls.size()), timers);
    timers.endFrame(false);

    const gl::Texture& illum = gather.illumination();
    const std::vector<float> a = illum.readFloats(0, 4);
    const std::vector<float> pos = frame.readPositions();
    const int L = gather.coarsestLevel();
    std::vector<int> marked(std::size_t(L) + 1, 0);
    const auto alpha = [&](int l, int x, int y) {
        const glm::ivec4 r = gather.levelRect(l);
        return a[(std::size_t(r.y + y) * illum.width() + std::size_t(r.x + x)) * 4 + 3];
    };
    for (int l = 0; l <= L; ++l) {
        const glm::ivec4 r = gather.levelRect(l);
        for (int y = 0; y < r.w; ++y)
            for (int x = 0; x < r.z; ++x) marked[l] += alpha(l, x, y) >= 1.0f;
    }
    int bad = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            int covering = 0;
            for (int l = 0; l <= L; ++l) covering += alpha(l, x >> l, y >> l) >= 1.0f;
            const bool geometry = pos[(std::size_t(y) * w + x) * 4 + 3] != 0.0f;
            // Background pixels inside a coarse patch are covered by it (their light is multiplied by 0).
            if ((geometry ? covering != 1 : covering > 1) && ++bad <= 5)
                ADD_FAILURE() << w << "x" << h << ": pixel " << x << "," << y << " (GL rows) covered " << covering
                              << " times, geometry " << geometry;
        }
    EXPECT_EQ(bad, 0);
    const std::vector<int> perLevel = gather.fragmentsPerLevel();
    ASSERT_EQ(perLevel.size(), marked.size());
    for (int l = 0; l <= L; ++l) EXPECT_EQ(perLevel[l], marked[l]) << "level " << l << ": stencil count vs gathered";
    const std::vector<gl::Counter> cs = gather.counters();
    double sum = 0.0;
    for (int l = 0; l <= L; ++l) sum += counter(cs, "fragments.level" + std::to_string(l));
    EXPECT_EQ(sum, counter(cs, "fragments.total"));
    expectFinite(frame.read(frame.indirect()), "indirect");
    if (perLevelOut) *perLevelOut = perLevel;
}

TEST_F(IsrMultiresTest, EveryPixelCoveredExactlyOnce)
{
    gl::MultiresSettings s; // default thresholds, 16 x 16 coarsest patches: a real mix of levels at 64 x 64
    s.coarsestLevel = 4;
    std::vector<int> perLevel;
    checkCoverage(64, 64, s, &perLevel);
    int coarse = 0;
    for (std::size_t l = 1; l < perLevel.size(); ++l) coarse += perLevel[l];
    EXPECT_GT(coarse, 0) << "default thresholds should leave some patches coarse";
    checkCoverage(333, 200, s);
    checkCoverage(1, 1, s);
    checkCoverage(7, 3, s);
    s.coarsestLevel = 2;
    checkCoverage(45, 31, s);
    s.depthThreshold = 10.0f; // nothing is a discontinuity: all at the coarsest level where geometry is
    s.normalThreshold = 4.0f;
    checkCoverage(45, 31, s);
}

// The upsampling runs as a fragment pass on a software rasteriser and as a compute pass on a GPU
// (gl/frame/multires.h): the two stages, one shader body, must write the same image.
TEST_F(IsrMultiresTest, UpsamplingAsFragmentsEqualsUpsamplingAsCompute)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    gl::PassTimers timers;
    const auto framePtr = testFrame(scene, 333, 200, timers); // odd sizes: partial patches at every level
    gl::Frame& frame = *framePtr;
    const std::vector<GpuVpl> vpls = {{{0.3f, 0.0f, 0.3f, 1e-3f}, {0, 1, 0, 0}, {0.01f, 0.01f, 0.01f, 0}},
                                      {{0.55f, 0.3f, 0.3f, 1e-3f}, {-1, 0, 0, 0}, {0.02f, 0.0f, 0.0f, 0}}};
    const gl::Buffer cache = vplCache(vpls);
    gl::MultiresSettings s;
    s.coarsestLevel = 4;
    gl::MultiresGather gather(frame, s);
    std::vector<float> images[2];
    for (bool asFragments : {true, false}) {
        gather.pyramid().setUpsampleAsFragments(asFragments);
        frame.clearIndirect();
        gather.run(frame, cache, int(vpls.size()), timers);
        timers.endFrame(false);
        images[asFragments ? 0 : 1] = frame.indirect().readFloats(0, 4);
    }
    int lit = 0;
    float worst = 0.0f;
    for (std::size_t i = 0; i < images[0].size(); ++i) {
        worst = std::max(worst, std::abs(images[0][i] - images[1][i]));
        lit += i % 4 == 0 && images[0][i] > 0.0f;
    }
    EXPECT_GT(lit, 10000);
    EXPECT_LT(worst, 1e-6f) << "the same arithmetic in both stages";
}

// ---------------------------------------------------------------------------------------------------
// Equal to the full-resolution gathers at zero thresholds.

// Both thresholds 0: every pixel is its own fragment (level 0), gathered at its own G-buffer position,
// normal and albedo, so multires-gather equals rsm's per-pixel gather of the same regular-grid VPLs.
// Tolerance 1e-3 relative RMSE (the bound; only the float summation differs).
TEST_F(IsrMultiresTest, ZeroThresholdsEqualFullResolutionGather)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    for (const auto& [w, h] : {std::pair{64, 64}, std::pair{333, 200}}) {
        const std::string size = std::to_string(w) + "x" + std::to_string(h);
        const Rendered m =
            render(scene, "multires-gather",
                   {{"vpls", "64"}, {"rsmSize", "32"}, {"depthThreshold", "0"}, {"normalThreshold", "0"}}, w, h);
        const Rendered r = render(scene, "rsm", {{"vpls", "64"}, {"rsmSize", "32"}}, w, h);
        testing::expectImagesClose("multires-zero-vs-rsm-" + size, m.indirect, r.indirect,
                                   testing::ImageMetric::relativeRmse(), 1e-3,
                                   "the issue's bound: only the float summation order differs");
        EXPECT_EQ(counter(m.counters, "fragments.level0"), geometryPixels(m.position)) << size;
        EXPECT_EQ(counter(m.counters, "fragments.total"), geometryPixels(m.position)) << size;
        EXPECT_EQ(counter(m.counters, "vpls"), 64.0);
    }
}

// The same equality against an independent path: the regular-grid VPLs of the cache read back and
// gathered on the CPU in double at every pixel's own G-buffer values (Eqs. 1 and 5), compared with
// MultiresGather at zero thresholds over the same cache. Tolerance 1e-3 relative RMSE (float vs double).
TEST_F(IsrMultiresTest, ZeroThresholdsEqualCpuGather)
{
    constexpr double kPi = 3.14159265358979323846;
    const core::Scene scene = core::makeCornell("cornell-spot");
    for (const auto& [w, h] : {std::pair{64, 64}, std::pair{333, 200}}) {
        gl::PassTimers timers;
        const auto framePtr = testFrame(scene, w, h, timers);
        gl::Frame& frame = *framePtr;
        gl::RsmSettings rs;
        rs.size = 32;
        gl::RsmPass rsm(rs);
        gl::VplSampler sampler;
        gl::Buffer cache("test.cache", gl::vplCacheBytes(64));
        gl::MultiresSettings ms;
        ms.depthThreshold = 0.0f;
        ms.normalThreshold = 0.0f;
        gl::MultiresGather gather(frame, ms);
        frame.clearIndirect();
        rsm.render(frame, timers);
        const int count = sampler.sample(rsm, cache, 8, timers);
        gather.run(frame, cache, count, timers);
        timers.endFrame(false);
        ASSERT_EQ(count, 64);

        std::vector<GpuVpl> vpls = cache.download<GpuVpl>();
        vpls.resize(std::size_t(count)); // the cache holds whole blocks; what lies past count is not VPLs
        const std::vector<float> P = frame.readPositions(), N = frame.readNormals(),
                                 D = frame.diffuse().readFloats(0, 4);
        core::Image want(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t i = (std::size_t(y) * w + x) * 4;
                if (P[i + 3] == 0.0f) continue;
                const glm::dvec3 p(P[i], P[i + 1], P[i + 2]), n(N[i], N[i + 1], N[i + 2]),
                    rho(D[i], D[i + 1], D[i + 2]);
                glm::dvec3 sum(0.0);
                for (const GpuVpl& v : vpls) {
                    const glm::dvec3 d = glm::dvec3(v.positionArea) - p;
                    const double r2 = glm::dot(d, d), r = std::sqrt(r2);
                    const glm::dvec3 wv = r > 0.0 ? d / r : n;
                    const double cosI = std::max(glm::dot(n, wv), 0.0);
                    const double cosJ = std::max(glm::dot(glm::dvec3(v.normal), -wv), 0.0);
                    sum += rho / kPi * glm::dvec3(v.flux) * (cosI * cosJ / (kPi * r2 + double(v.positionArea.w)));
                }
                want.set(x, h - 1 - y, glm::vec3(sum));
            }
        const std::string size = std::to_string(w) + "x" + std::to_string(h);
        testing::expectImagesClose("multires-zero-vs-cpu-" + size, frame.read(frame.indirect()), want,
                                   testing::ImageMetric::relativeRmse(), 1e-3,
                                   "the issue's bound: float on the GPU against double on the CPU");
        const std::vector<int> perLevel = gather.fragmentsPerLevel();
        int geometry = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) geometry += P[(std::size_t(y) * w + x) * 4 + 3] != 0.0f;
        EXPECT_EQ(perLevel.at(0), geometry) << size << ": every pixel with geometry is a level-0 fragment";
    }
}

// tau = 0 refines every cluster down to single RSM texels, and with zero eye-space thresholds every pixel
// is a fragment: hisr then equals rsm-full at the same RSM size (relative RMSE below 1e-3).
TEST_F(IsrMultiresTest, HisrTauZeroEqualsRsmFull)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    const Rendered hisr = render(
        scene, "hisr",
        {{"rsmSize", "32"}, {"tau", "0"}, {"topGrid", "8"}, {"depthThreshold", "0"}, {"normalThreshold", "0"}}, 48, 48);
    const Rendered full = render(scene, "rsm-full", {{"rsmSize", "32"}}, 48, 48);
    testing::expectImagesClose("hisr-tau0-vs-rsm-full", hisr.indirect, full.indirect,
                               testing::ImageMetric::relativeRmse(), 1e-3,
                               "the same sum over single texels in another order, float");
    // Every fragment gathered every lit texel: no more clusters than texels, and at least some of them.
    const double perFragment = counter(hisr.counters, "clusters.perFragment");
    EXPECT_LE(perFragment, 32.0 * 32.0);
    EXPECT_GT(perFragment, 100.0);
}

// With hisr's tree and a positive tau: fewer clusters per fragment than texels, and the error against
// rsm-full grows with tau and stays within bounds set from measurements. At tau 1e-5 Eq. 8 refines
// nearly every cluster here (measured 0.011% relative RMSE, 2650 of 4096 texels per fragment): at most
// 0.3%. At tau 1e-4 (a quarter of the clusters) measured 8.0%, at most 10%: above the 3-4% of the
// paper's Fig. 13, which is measured on its own scenes at 256^2 with its eye-space patches; on
// cornell-spot a cluster's mean position between two surfaces is a poor VPL (gl/technique/isr/README.md).
TEST_F(IsrMultiresTest, HisrClustersDropAsTauGrows)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    // The paper's tree (no light-space discontinuity departures), every pixel a fragment.
    const Sets eye = {{"rsmSize", "64"},
                      {"depthThreshold", "0"},
                      {"normalThreshold", "0"},
                      {"lightDepthThreshold", "1e30"},
                      {"lightNormalThreshold", "1e30"}};
    double previous = 1e30, previousError = 0.0;
    const Rendered full = render(scene, "rsm-full", {{"rsmSize", "64"}}, 32, 32);
    for (const auto& [tau, bound] : {std::pair{"0", 1e-3}, std::pair{"1e-5", 3e-3}, std::pair{"1e-4", 0.1},
                                     std::pair{"1e-3", 0.2}, std::pair{"1", 0.3}}) {
        Sets s = eye;
        s.push_back({"tau", tau});
        const Rendered r = render(scene, "hisr", s, 32, 32);
        expectFinite(r.indirect, std::string("hisr tau ") + tau);
        const double perFragment = counter(r.counters, "clusters.perFragment");
        const double err = core::relativeRmse(r.indirect, full.indirect);
        std::printf("[ measured ] hisr tau %s against rsm-full: relative RMSE %.4g, %.1f clusters per fragment\n", tau,
                    err, perFragment);
        EXPECT_LT(perFragment, previous) << "tau " << tau;
        EXPECT_LE(err, bound) << "tau " << tau;
        EXPECT_GE(err, previousError) << "tau " << tau << ": coarser clusters, no smaller error";
        previous = perFragment;
        previousError = err;
    }
    EXPECT_LE(previous, 16.0 * 16.0) << "tau above the light's intensity never refines: the 16x16 top patches";
}

// The per-fragment traversal against an independent one on the CPU: the tree built from the same RSM is
// read back and walked recursively at every pixel (zero eye-space thresholds: every pixel a fragment at
// its G-buffer position) with Eq. 8 and the discontinuity departure, at a tau that refines some clusters
// and not others; the sum of Eqs. 1 and 5 over the chosen clusters (double) must match the gather (1e-3
// relative RMSE: float sums, and a cluster whose Eq. 8 test is a tie in float may go either way), and so
// must the number of clusters gathered (0.1%). Both forms of the gather: the paper's stenciled quad and
// the compute pass over the listed valid fragments (what a GPU runs, MultiresGather::gatherAsFragments).
TEST_F(IsrMultiresTest, HisrTraversalMatchesCpuTraversal)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    constexpr int kSize = 24, kRsm = 32;
    const double tau = 1e-3;
    std::vector<std::pair<std::string, Rendered>> forms;
    for (const char* form : {"fragments", "compute"})
        forms.emplace_back(form, render(scene, "hisr",
                                        {{"rsmSize", std::to_string(kRsm)},
                                         {"tau", "1e-3"},
                                         {"topGrid", "4"},
                                         {"depthThreshold", "0"},
                                         {"normalThreshold", "0"},
                                         {"lightRefineLevel", "1"},
                                         {"gather", form}},
                                        kSize, kSize));

    // The same RSM and tree, built again (both are deterministic), and the frame's G-buffer.
    gl::PassTimers timers;
    const auto framePtr = testFrame(scene, kSize, kSize, timers);
    gl::Frame& frame = *framePtr;
    gl::RsmSettings rs;
    rs.size = kRsm;
    gl::RsmPass rsm(rs);
    gl::VplTree tree(4); // as topGrid=4 and hisr's default light thresholds
    rsm.render(frame, timers);
    tree.build(rsm, timers);
    timers.endFrame(false);
    const std::vector<Node> nodes = tree.nodes().download<Node>();
    // Eq. 8's T from the paper, not from the code under test: T = 2 (I - tau) / (3 tau RSM_res^2), with I
    // the light's peak intensity (W/sr: the spot's brightest channel).
    const glm::vec3 I3 = scene.lights.at(0).intensity;
    const double I = std::max({I3.x, I3.y, I3.z});
    const float T = float(2.0 * (I - tau) / (3.0 * tau * double(kRsm) * double(kRsm)));
    ASSERT_GT(T, 0.0f);
    const std::vector<float> P = frame.readPositions(), N = frame.readNormals(), D = frame.diffuse().readFloats(0, 4);

    constexpr double kPi = 3.14159265358979323846;
    core::Image want(kSize, kSize);
    double clusters = 0.0;
    int fragments = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const std::size_t i = (std::size_t(y) * kSize + x) * 4;
            if (P[i + 3] == 0.0f) continue;
            ++fragments;
            const glm::vec3 p(P[i], P[i + 1], P[i + 2]);
            const glm::dvec3 n = glm::normalize(glm::dvec3(N[i], N[i + 1], N[i + 2]));
            glm::dvec3 sum(0.0);
            // Recursive walk of one subtree: node `code` of level m.
            const std::function<void(int, int, int)> walk = [&](int root, int m, int code) {
                const Node& c = nodes[std::size_t(root * tree.subtreeNodes() + tree.levelOffset(m) + code)];
                if (std::max({c.flux.x, c.flux.y, c.flux.z}) <= 0.0f) return;
                const glm::vec3 d = glm::vec3(c.positionArea) - p;
                const bool refine =
                    m > 0 && (glm::dot(d, d) <= T * c.normal.w * c.normal.w || (m > 1 && c.normal.w < 0.0f));
                if (refine) {
                    for (int k = 0; k < 4; ++k) walk(root, m - 1, 4 * code + k);
                    return;
                }
                const glm::dvec3 dd(d), nj = glm::length(glm::dvec3(c.normal)) > 0.0
                                                 ? glm::normalize(glm::dvec3(c.normal))
                                                 : glm::dvec3(0.0);
                const double r2 = glm::dot(dd, dd), r = std::sqrt(r2);
                const double cosI = std::max(glm::dot(n, dd / r), 0.0), cosJ = std::max(-glm::dot(nj, dd / r), 0.0);
                sum += glm::dvec3(c.flux) / kPi * (cosI * cosJ / (kPi * r2 + double(c.positionArea.w)));
                clusters += 1.0;
            };
            for (int root = 0; root < tree.rootCount(); ++root) walk(root, tree.depth(), 0);
            want.set(x, kSize - 1 - y, glm::vec3(sum * glm::dvec3(D[i], D[i + 1], D[i + 2])));
        }
    for (const auto& [form, gpu] : forms) {
        SCOPED_TRACE("gather as " + form);
        testing::expectImagesClose("hisr-" + form + "-vs-cpu-traversal", gpu.indirect, want,
                                   testing::ImageMetric::relativeRmse(), 1e-3,
                                   "float sums; an Eq. 8 tie in float may go either way");
        EXPECT_NEAR(counter(gpu.counters, "clusters.gathered"), clusters, 1e-3 * clusters);
        EXPECT_EQ(counter(gpu.counters, "fragments.level0"), double(fragments));
    }
    // Some clusters were refined and some were not: the test exercised both branches of Eq. 8.
    EXPECT_GT(clusters / fragments, double(tree.rootCount()));
    EXPECT_LT(clusters / fragments, double(kRsm * kRsm) / 2.0);
}

// The passes written in two forms choose by the probe's ceilings when the application knows them: an
// NVIDIA H200's (fragment FMA 1.8 TFLOP/s, compute 48) give compute passes, llvmpipe's (58 and 35 GFLOP/s)
// fragment passes; without them the renderer's kind decides (fragments on a software rasteriser).
TEST_F(IsrMultiresTest, AutoFormsFollowTheProbesCeilings)
{
    struct Forget {
        ~Forget() { gl::setKnownCeilings(std::nullopt); }
    } forget;
    gl::Ceilings h200;
    h200.renderer = "NVIDIA H200/PCIe/SSE2";
    h200.fragmentGflops = 1828.3;
    h200.computeGflops = 47647.8;
    gl::setKnownCeilings(h200);
    EXPECT_FALSE(gl::preferFragmentPasses());
    EXPECT_FALSE(gl::MultiresGather::defaultGatherAsFragments());
    EXPECT_TRUE(gl::Interpolation::defaultAsCompute());
    gl::Ceilings llvmpipe = h200;
    llvmpipe.renderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
    llvmpipe.fragmentGflops = 58.2;
    llvmpipe.computeGflops = 34.9;
    gl::setKnownCeilings(llvmpipe);
    EXPECT_TRUE(gl::MultiresGather::defaultGatherAsFragments());
    EXPECT_FALSE(gl::Interpolation::defaultAsCompute());
    gl::setKnownCeilings(std::nullopt);
    EXPECT_EQ(gl::preferFragmentPasses(), gl::softwareRasterizer());
}

// The gathers' two forms (the paper's stenciled quad, and the compute pass over the listed valid fragments
// that a GPU runs) at a size with partial patches at every level, with gathers split over several draws
// (hisr's default tree under llvmpipe's loop budget, 1024 VPLs in uniform blocks: each compute dispatch
// adds to what the last wrote): the same fragments, clusters and light. hisr's compute walk shares each
// fragment among 16 invocations by default (one top patch in 16 each, summed in lane order), and among 64,
// more than a draw's top patches under llvmpipe's budget: lanes without a patch add nothing.
TEST_F(IsrMultiresTest, GatherAsComputeEqualsGatherAsFragments)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    for (const auto& [technique, sets] : {std::pair<std::string, Sets>{"hisr", {}},
                                          {"hisr", {{"gatherLanes", "64"}, {"topGrid", "4"}}},
                                          {"multires-gather", {{"vpls", "1024"}}},
                                          {"isr", {{"minLevel", "1"}}}}) {
        SCOPED_TRACE(technique);
        Rendered r[2];
        for (int i = 0; i < 2; ++i) {
            Sets s = sets;
            s.push_back({"gather", i == 0 ? "fragments" : "compute"});
            s.push_back({"coarsestLevel", "3"});
            r[i] = render(scene, technique, s, 61, 37);
        }
        std::vector<std::string> same = {"fragments.total", "fragments.level1", "fragments.level3"};
        if (technique == "hisr") same.push_back("clusters.gathered");
        for (const std::string& c : same) EXPECT_EQ(counter(r[0].counters, c), counter(r[1].counters, c)) << c;
        EXPECT_GT(counter(r[0].counters, "fragments.level3"), 0.0);
        // hisr's lanes regroup its sum into partial sums: float rounding (1.2e-6 on an NVIDIA H200).
        testing::expectImagesClose(technique + "-compute-vs-fragments", r[1].indirect, r[0].indirect,
                                   testing::ImageMetric::relativeRmse(), technique == "hisr" ? 4e-6 : 1e-6,
                                   "one sum, two stages");
    }
}

// hisr's lanes per fragment (gatherLanes=auto): powers of two from 1 to 16 that keep the dispatch at 2^17
// invocations, more for fewer fragments; the first frame (no count) takes 4.
TEST(HisrGatherLanes, FillTheDispatchWithPowersOfTwo)
{
    EXPECT_EQ(gl::hisrGatherLanes(0), 4);
    EXPECT_EQ(gl::hisrGatherLanes(1), 16);
    EXPECT_EQ(gl::hisrGatherLanes(28310), 4);   // the Cornell box at 1024x768
    EXPECT_EQ(gl::hisrGatherLanes(130626), 1);  // Sponza at 1024x768
    EXPECT_EQ(gl::hisrGatherLanes(5000000), 1); // more than the dispatch target
    int previous = 16;
    for (unsigned n = 1; n < 400000; n = n * 3 / 2 + 1) {
        const int lanes = gl::hisrGatherLanes(n);
        EXPECT_TRUE(lanes >= 1 && lanes <= 16 && (lanes & (lanes - 1)) == 0) << n;
        EXPECT_TRUE(lanes == 1 || std::uint64_t(n) * lanes <= (1u << 17)) << n;
        EXPECT_LE(lanes, previous) << n;
        previous = lanes;
    }
}

// Larger thresholds merge more pixels into coarser patches: the number of valid fragments drops.
TEST_F(IsrMultiresTest, FragmentsDropAsThresholdsGrow)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    double previous = 1e30;
    for (const auto& [d, n] :
         {std::pair{"0", "0"}, std::pair{"0.005", "0.05"}, std::pair{"0.03", "0.15"}, std::pair{"0.2", "0.5"}}) {
        const Rendered r = render(
            scene, "multires-gather",
            {{"vpls", "16"}, {"rsmSize", "32"}, {"depthThreshold", d}, {"normalThreshold", n}, {"coarsestLevel", "4"}},
            96, 96);
        const double total = counter(r.counters, "fragments.total");
        EXPECT_LT(total, previous) << "thresholds " << d << ", " << n;
        previous = total;
        expectFinite(r.indirect, "multires-gather");
    }
}

// ---------------------------------------------------------------------------------------------------
// Multiresolution splatting [NW09] (multires-splat) against the stencil and the gather.

// The iterative refinement selects exactly the stencil pass's valid fragments (the same count per level,
// the same neighbour marks at every texel of the flattened buffer), and splatting every VPL to them adds up
// to what the stenciled gather computes (1e-5 relative: the same float terms in another order), at a
// power-of-two size with 16 x 16 coarsest patches, at 333 x 200 with the automatic level, and at 1 x 1.
TEST_F(IsrMultiresTest, RefineAndSplatEqualStencilAndGather)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    std::vector<GpuVpl> vpls;
    for (int i = 0; i < 40; ++i) // a spread of VPLs on the floor, the walls and the ceiling
        vpls.push_back({{0.05f + 0.0113f * i, i % 3 == 0 ? 0.0f : 0.02f * i, 0.1f + 0.009f * i, 1e-3f},
                        {0.0f, i % 2 ? 1.0f : -1.0f, 0.0f, 0.0f},
                        {0.01f, 0.005f * (i % 4), 0.002f, 0.0f}});
    for (const auto& [w, h, coarsest] : {std::tuple{64, 64, 4}, std::tuple{333, 200, -1}, std::tuple{1, 1, -1}}) {
        const std::string size = std::to_string(w) + "x" + std::to_string(h);
        gl::PassTimers timers;
        const auto framePtr = testFrame(scene, w, h, timers);
        gl::Frame& frame = *framePtr;
        const gl::Buffer cache = vplCache(vpls);
        gl::MultiresSettings ms;
        ms.coarsestLevel = coarsest;
        gl::MultiresGather gather(frame, ms);

        gather.run(frame, cache, int(vpls.size()), timers);
        const std::vector<float> stenciled = gather.illumination().readFloats(0, 4);
        const std::vector<int> stencilCounts = gather.fragmentsPerLevel();
        const core::Image gathered = frame.read(frame.indirect());

        gather.buildPyramid(frame, timers);
        const int points = gather.refine(frame, timers);
        gather.splat(frame, cache, int(vpls.size()), timers);
        gather.upsample(frame, timers);
        timers.endFrame(false);
        const std::vector<float> splatted = gather.illumination().readFloats(0, 4);
        EXPECT_EQ(gather.fragmentsPerLevel(), stencilCounts) << size;
        int total = 0;
        for (int c : stencilCounts) total += c;
        EXPECT_GT(points, 0) << size;
        EXPECT_LE(points, total) << size << ": one point per valid fragment that reflects light";
        ASSERT_EQ(splatted.size(), stenciled.size());
        int marks = 0, light = 0;
        for (std::size_t i = 0; i < stenciled.size(); i += 4) {
            if (splatted[i + 3] != stenciled[i + 3] && ++marks <= 3)
                ADD_FAILURE() << size << ": texel " << i / 4 << " marked " << splatted[i + 3] << " by the refinement, "
                              << stenciled[i + 3] << " by the stencil pass";
            for (int c = 0; c < 3; ++c)
                if (std::abs(splatted[i + c] - stenciled[i + c]) > 1e-5f * std::abs(stenciled[i + c]) + 1e-12f &&
                    ++light <= 3)
                    ADD_FAILURE() << size << ": texel " << i / 4 << " splatted " << splatted[i + c] << ", gathered "
                                  << stenciled[i + c];
        }
        EXPECT_EQ(marks, 0) << size;
        EXPECT_EQ(light, 0) << size;
        if (total > 1)
            testing::expectImagesClose("splat-vs-gather-" + size, frame.read(frame.indirect()), gathered,
                                       testing::ImageMetric::relativeRmse(), 1e-5,
                                       "the same float terms summed in another order");
    }
}

// ---------------------------------------------------------------------------------------------------
// The VPL tree against a CPU rebuild from the same RSM.

// Reads the RSM back, builds every cluster on the CPU (sums, area-weighted means, max light distance)
// by walking the layout of glsl/technique/isr/vpl_tree.glsl independently (row-major patches, explicit
// bit interleaving), and compares each node (normals: the area-weighted mean vector, not renormalised). Tolerances: 1e-4 relative on sums (float order), 1e-4 m on
// positions, 1e-3 on normals.
TEST_F(IsrMultiresTest, VplTreeMatchesCpuClusters)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    gl::PassTimers timers;
    const auto framePtr = testFrame(scene, 8, 8, timers, false);
    gl::Frame& frame = *framePtr;
    gl::RsmSettings rs;
    rs.size = 32;
    gl::RsmPass rsm(rs);
    gl::VplTree tree(4); // 4 x 4 top patches of 8 x 8 texels: depth 3
    rsm.render(frame, timers);
    tree.build(rsm, timers);
    timers.endFrame(false);
    ASSERT_EQ(rsm.viewCount(), 1);
    ASSERT_EQ(tree.depth(), 3);
    ASSERT_EQ(tree.subtreeNodes(), 1 + 4 + 16 + 64);
    ASSERT_EQ(tree.rootCount(), 16);

    const std::vector<float> P = rsm.position().readFloats(0, 4), N = rsm.normal().readFloats(0, 4),
                             F = rsm.flux().readFloats(0, 4);
    const glm::vec3 origin = rsm.views()[0].origin;
    static_assert(sizeof(Node) == gl::VplTree::kNodeBytes);
    const std::vector<Node> got = tree.nodes().download<Node>();
    ASSERT_EQ(got.size(), std::size_t(tree.nodeCount()));
    const auto interleave = [](int x, int y) {
        int c = 0;
        for (int b = 0; b < 8; ++b) c |= ((x >> b) & 1) << (2 * b) | ((y >> b) & 1) << (2 * b + 1);
        return c;
    };
    glm::dvec3 rootFlux(0.0), rsmFlux(0.0);
    int checked = 0;
    for (int ty = 0; ty < 4; ++ty)
        for (int tx = 0; tx < 4; ++tx)
            for (int m = 0; m <= 3; ++m) {
                const int side = 8 >> m;
                for (int cy = 0; cy < side; ++cy)
                    for (int cx = 0; cx < side; ++cx) {
                        glm::dvec3 pos(0.0), nrm(0.0), flux(0.0);
                        double area = 0.0, omega = 0.0, dist = 0.0;
                        for (int y = 0; y < (1 << m); ++y)
                            for (int x = 0; x < (1 << m); ++x) {
                                const int X = tx * 8 + (cx << m) + x, Y = ty * 8 + (cy << m) + y;
                                const std::size_t i = (std::size_t(Y) * 32 + X) * 4;
                                const double a = N[i + 3];
                                pos += a * glm::dvec3(P[i], P[i + 1], P[i + 2]);
                                nrm += a * glm::dvec3(N[i], N[i + 1], N[i + 2]);
                                area += a;
                                flux += glm::dvec3(F[i], F[i + 1], F[i + 2]);
                                omega += F[i + 3];
                                if (P[i + 3] != 0.0f)
                                    dist = std::max(dist,
                                                    double(glm::length(glm::vec3(P[i], P[i + 1], P[i + 2]) - origin)));
                                if (m == 0) rsmFlux += glm::dvec3(F[i], F[i + 1], F[i + 2]);
                            }
                        const int subtree = ty * 4 + tx;
                        const Node& n =
                            got[std::size_t(subtree * tree.subtreeNodes() + tree.levelOffset(m) + interleave(cx, cy))];
                        const std::string where = "top " + std::to_string(tx) + "," + std::to_string(ty) + " level " +
                                                  std::to_string(m) + " node " + std::to_string(cx) + "," +
                                                  std::to_string(cy);
                        for (int c = 0; c < 3; ++c) ASSERT_NEAR(n.flux[c], flux[c], 1e-4 * flux[c] + 1e-12) << where;
                        ASSERT_NEAR(n.flux.w, omega, 1e-4 * omega + 1e-12) << where;
                        ASSERT_NEAR(n.positionArea.w, area, 1e-4 * area + 1e-12) << where;
                        ASSERT_NEAR(std::abs(n.normal.w), dist, 1e-5) << where;
                        if (area > 0.0) {
                            const glm::dvec3 mean = pos / area, unit = nrm / area;
                            for (int c = 0; c < 3; ++c) {
                                ASSERT_NEAR(n.positionArea[c], mean[c], 1e-4) << where;
                                ASSERT_NEAR(n.normal[c], unit[c], 1e-3) << where;
                            }
                        }
                        if (m == 3) rootFlux += glm::dvec3(n.flux);
                        ++checked;
                    }
            }
    EXPECT_EQ(checked, tree.nodeCount());
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(rootFlux[c], rsmFlux[c], 1e-4 * rsmFlux[c]) << "the roots hold the RSM's flux";
    EXPECT_GT(rsmFlux.x, 0.0);
}

// Eq. 8's constant: T = 2 (I - tau) / (3 tau RSM_res^2), infinite at tau = 0; I from the lights (W/sr).
TEST(IsrMultiresEquations, HisrRefineConstant)
{
    EXPECT_NEAR(gl::hisrRefineConstant(0.5, 1e-3, 256), 2.0 * (0.5 - 1e-3) / (3.0 * 1e-3 * 65536.0), 1e-12);
    EXPECT_TRUE(std::isinf(gl::hisrRefineConstant(0.5, 0.0, 256)));
    EXPECT_LT(gl::hisrRefineConstant(0.5, 1.0, 256), 0.0) << "tau above I: never refine";
    gl::LightSource spot;
    spot.type = gl::kLightSpot;
    spot.intensity = {0.23205f, 0.1638f, 0.0546f};
    EXPECT_NEAR(gl::hisrPeakIntensity({spot}), 0.23205, 1e-7);
}

// ---------------------------------------------------------------------------------------------------
// Odd viewports.

// 333 x 200 (not a power of two, odd) and 1 x 1 (no level above the pixel): both techniques run without
// a GL error (the fixture fails on any) and write finite light; the 1 x 1 image is a single fragment.
TEST_F(IsrMultiresTest, OddAndOnePixelViewports)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    for (const char* technique : {"multires-gather", "hisr"}) {
        const Sets s = {{"rsmSize", "32"}};
        const Rendered a = render(scene, technique, s, 333, 200);
        expectFinite(a.indirect, std::string(technique) + " 333x200");
        double sum = 0.0;
        for (float v : a.indirect.rgb) sum += v;
        EXPECT_GT(sum, 0.0) << technique;
        EXPECT_LT(counter(a.counters, "fragments.total"), 333.0 * 200.0 / 2.0) << technique << ": patches merge";
        const Rendered b = render(scene, technique, s, 1, 1);
        expectFinite(b.indirect, std::string(technique) + " 1x1");
        EXPECT_EQ(counter(b.counters, "fragments.total"), double(geometryPixels(b.position))) << technique;
    }
}

} // namespace
} // namespace bounce
