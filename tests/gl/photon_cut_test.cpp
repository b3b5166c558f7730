// The photon tree and the illumination cut (gl/technique/photon/photon_tree.h, illumination_cut.h)
// against their invariants: every node holds its heap range of photons and its children's sums; the
// cut covers every photon exactly once and keeps the photon count and power, before and after
// refinement; after refinement every cut node passed the 1.2 x test, is a leaf, or entered the cut in
// the last iteration; the same photons give the same cut; a node of one photon (r = 0) stays finite.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "gl/frame/frame.h"
#include "gl/frame/ray_caster.h"
#include "gl/technique/photon/illumination_cut.h"
#include "gl/technique/photon/photon_tracer.h"
#include "gl/technique/photon/photon_tree.h"
#include "tests/gl/gl_test_fixture.h"
#include "tests/gl/photon_test_scenes.h"

namespace bounce {
namespace {

struct Built {
    std::vector<gl::GpuPhoton> photons;
    std::vector<gl::GpuPhotonNode> nodes;
    std::vector<gl::GpuCutNode> cut;
    std::vector<std::uint32_t> list;
    std::vector<std::uint32_t> splits;
    int depth = 0;
    float eMin = 0.0f;
};

Built buildFrom(const gl::Buffer& photons, std::uint32_t count, int leafPhotons,
                const gl::IlluminationCutSettings& cutSettings, gl::Buffer& counters, float minRadius)
{
    gl::PassTimers timers;
    gl::PhotonTree tree(leafPhotons);
    tree.build(photons, count, minRadius, timers);
    gl::IlluminationCut cut;
    cut.build(tree, photons, cutSettings, counters, timers);
    Built b;
    b.nodes = tree.download();
    b.cut = cut.download();
    b.list = cut.downloadList();
    b.splits = cut.splitsPerIteration();
    b.depth = tree.depth();
    b.eMin = cut.eMin();
    return b;
}

Built buildScene(const core::Scene& scene, int photons, const gl::IlluminationCutSettings& cutSettings)
{
    gl::Frame frame(scene, photontest::smallFrame(8, 8));
    gl::RayCaster caster(scene);
    gl::Buffer counters("photon.counters", gl::kCounterSlots * 4);
    gl::PhotonTracerSettings ts;
    ts.photons = photons;
    gl::PhotonTracer tracer(ts);
    gl::PassTimers timers;
    tracer.trace(frame, caster, counters, timers);
    Built b =
        buildFrom(tracer.photons(), tracer.storedCount(), 16, cutSettings, counters, tracer.sceneSize() / 4096.0f);
    b.photons = tracer.downloadPhotons();
    return b;
}

std::uint32_t flagsOf(const gl::GpuCutNode& c)
{
    std::uint32_t f;
    std::memcpy(&f, &c.influenceLo.w, 4);
    return f;
}
std::uint32_t generationOf(const gl::GpuCutNode& c)
{
    std::uint32_t g;
    std::memcpy(&g, &c.influenceHi.w, 4);
    return g;
}

// Every node's count is its heap range's size and its power its photons' sum; the root holds them all.
void expectTreeHoldsItsPhotons(const Built& b)
{
    const auto n = std::uint32_t(b.photons.size());
    int wrongCount = 0, wrongBox = 0, wrongPower = 0;
    for (std::uint32_t i = 1; i < b.nodes.size(); ++i) {
        const auto [lo, hi] = gl::PhotonTree::range(i, n);
        const gl::GpuPhotonNode& node = b.nodes[i];
        wrongCount += std::uint32_t(node.lo.w) != hi - lo;
        glm::dvec3 power(0.0);
        for (std::uint32_t p = lo; p < hi; ++p) {
            const glm::vec3 x(b.photons[p].positionPath);
            wrongBox +=
                glm::any(glm::lessThan(x, glm::vec3(node.lo))) || glm::any(glm::greaterThan(x, glm::vec3(node.hi)));
            power += glm::dvec3(glm::vec3(b.photons[p].powerIndex));
        }
        wrongPower += std::abs(power.x - node.power.x) > 1e-4 * std::max(power.x, 1e-9);
    }
    EXPECT_EQ(wrongCount, 0);
    EXPECT_EQ(wrongBox, 0);
    EXPECT_EQ(wrongPower, 0);
}

// Every non-empty leaf has exactly one cut node on its path to the root; the cut's counts and powers
// add up to the tree's; the list holds exactly the flagged nodes, in heap order.
void expectValidCut(const Built& b)
{
    const std::uint32_t leaves = 1u << b.depth;
    int uncovered = 0, twice = 0;
    for (std::uint32_t k = 0; k < leaves; ++k) {
        const std::uint32_t leaf = leaves + k;
        if (b.nodes[leaf].lo.w <= 0.0f) continue;
        int onPath = 0;
        for (std::uint32_t i = leaf; i >= 1; i >>= 1) onPath += (flagsOf(b.cut[i]) & gl::kCutIn) != 0;
        uncovered += onPath == 0;
        twice += onPath > 1;
    }
    EXPECT_EQ(uncovered, 0) << "leaves no cut node covers";
    EXPECT_EQ(twice, 0) << "leaves covered more than once";
    double count = 0.0;
    glm::dvec3 power(0.0);
    std::vector<std::uint32_t> flagged;
    for (std::uint32_t i = 1; i < b.nodes.size(); ++i)
        if (flagsOf(b.cut[i]) & gl::kCutIn) {
            flagged.push_back(i);
            count += b.nodes[i].lo.w;
            power += glm::dvec3(glm::vec3(b.nodes[i].power));
        }
    EXPECT_EQ(flagged, b.list);
    EXPECT_EQ(count, double(b.nodes[1].lo.w));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(power[c], b.nodes[1].power[c], 1e-5 * b.nodes[1].power[c] + 1e-12);
}

class PhotonCutTest : public GlTest {};

TEST_F(PhotonCutTest, TreeNodesHoldTheirPhotons)
{
    gl::IlluminationCutSettings s;
    const Built b = buildScene(core::makeCornell("cornell-spot"), 8192, s);
    ASSERT_GT(b.photons.size(), 1000u);
    expectTreeHoldsItsPhotons(b);
    for (std::uint32_t k = 0; k < (1u << b.depth); ++k) EXPECT_LE(b.nodes[(1u << b.depth) + k].lo.w, 16.0f);
}

// Before refinement (iterations = 0 still evaluates E_p) and after 4 iterations.
TEST_F(PhotonCutTest, CutCoversEveryPhotonOnceAndKeepsPower)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    for (int iterations : {0, 4}) {
        SCOPED_TRACE("iterations " + std::to_string(iterations));
        gl::IlluminationCutSettings s;
        s.eminLevel = 8;
        s.iterations = iterations;
        const Built b = buildScene(scene, 16384, s);
        std::printf("[ measured ] %zu photons, depth %d, E_min %.4g, cut %zu nodes after %d iterations\n",
                    b.photons.size(), b.depth, b.eMin, b.list.size(), iterations);
        ASSERT_GT(b.list.size(), 8u);
        expectValidCut(b);
    }
}

// After refinement: every cut node passed the test, is a leaf, or was made by the last iteration; each
// has a finite, non-negative irradiance.
TEST_F(PhotonCutTest, RefinedCutNodesPassOrAreLeavesOrHitTheCap)
{
    gl::IlluminationCutSettings s;
    s.eminLevel = 8;
    s.iterations = 3;
    const Built b = buildScene(core::makeCornell("cornell-area"), 16384, s);
    int passed = 0, leaves = 0, capped = 0, bad = 0, notFinite = 0;
    for (std::uint32_t i : b.list) {
        const std::uint32_t f = flagsOf(b.cut[i]);
        const bool leaf = int(std::bit_width(i)) - 1 == b.depth;
        if (f & gl::kCutPassed)
            ++passed;
        else if (leaf)
            ++leaves;
        else if (generationOf(b.cut[i]) == std::uint32_t(s.iterations))
            ++capped;
        else
            ++bad;
        const glm::vec4 e = b.cut[i].irradiance;
        notFinite += !(std::isfinite(e.x) && std::isfinite(e.y) && std::isfinite(e.z) && e.x >= 0 && e.y >= 0 &&
                       e.z >= 0 && e.w == 1.0f);
    }
    std::printf("[ measured ] cut %zu: passed %d, leaves %d, at the cap %d; splits per iteration:", b.list.size(),
                passed, leaves, capped);
    for (std::uint32_t n : b.splits) std::printf(" %u", n);
    std::printf("\n");
    EXPECT_EQ(bad, 0);
    EXPECT_EQ(notFinite, 0);
    EXPECT_GT(passed, 0);
    expectValidCut(b);
}

TEST_F(PhotonCutTest, SamePhotonsGiveTheSameCut)
{
    gl::IlluminationCutSettings s;
    s.eminLevel = 8;
    const core::Scene scene = core::makeCornell("cornell-point");
    // The second build's buffers start as 0xff bytes, the first's as llvmpipe gives them (zeros): a GPU
    // driver hands out whatever the memory held, so a byte no pass writes must not reach the result.
    const bool poisoned = gl::poisonNewStorage();
    gl::setPoisonNewStorage(false);
    const Built a = buildScene(scene, 8192, s);
    gl::setPoisonNewStorage(true);
    const Built b = buildScene(scene, 8192, s);
    gl::setPoisonNewStorage(poisoned);
    EXPECT_EQ(a.list, b.list);
    ASSERT_EQ(a.cut.size(), b.cut.size());
    // Node 0 is not a node (the tree is a heap from 1); every word of the others must agree.
    int differing = 0;
    for (std::size_t i = 1; i < a.cut.size(); ++i) {
        const auto* wa = reinterpret_cast<const std::uint32_t*>(&a.cut[i]);
        const auto* wb = reinterpret_cast<const std::uint32_t*>(&b.cut[i]);
        for (std::size_t w = 0; w < sizeof(gl::GpuCutNode) / 4; ++w)
            if (wa[w] != wb[w] && ++differing <= 5)
                ADD_FAILURE() << "cut node " << i << ", word " << w << ": " << wa[w] << " and " << wb[w];
    }
    EXPECT_EQ(differing, 0);
}

// Hard case: nodes of one photon, and of photons that coincide (box of size 0: r = 0 but for the floor),
// in a tree of five photons with leaves of one: Eq. 3 and the density estimate stay finite, the cut is
// valid.
TEST_F(PhotonCutTest, OnePhotonNodesStayFinite)
{
    std::vector<gl::GpuPhoton> photons(5);
    const glm::vec3 positions[5] = {{0, 0, 0}, {0, 0, 0}, {0.1f, 0, 0}, {0.1f, 0, 0.1f}, {0.5f, 0, 0.5f}};
    for (int i = 0; i < 5; ++i) {
        photons[i].positionPath = glm::vec4(positions[i], 0.0f);
        photons[i].powerIndex = glm::vec4(0.01f, 0.02f, 0.03f, 0.0f);
        photons[i].incoming = glm::vec4(0, 1, 0, 0);
        photons[i].normal = glm::vec4(0, 1, 0, 0);
    }
    gl::Buffer buffer = gl::Buffer::fromVector("test.photons", photons);
    gl::Buffer counters("photon.counters", gl::kCounterSlots * 4);
    gl::IlluminationCutSettings s;
    s.densityPhotons = 2.0f;
    Built b = buildFrom(buffer, 5, 1, s, counters, 1e-4f);
    b.photons = photons;
    EXPECT_EQ(b.depth, 3);
    expectTreeHoldsItsPhotons(b);
    expectValidCut(b);
    for (std::uint32_t i = 1; i < b.nodes.size(); ++i) {
        EXPECT_TRUE(std::isfinite(b.nodes[i].power.w)) << "E~ of node " << i;
        EXPECT_GE(b.nodes[i].hi.w, 1e-4f);
    }
    for (std::uint32_t i : b.list) {
        const glm::vec4 e = b.cut[i].irradiance;
        EXPECT_TRUE(std::isfinite(e.x) && e.x >= 0.0f) << "E_p of cut node " << i;
    }
}

} // namespace
} // namespace bounce
