// Alpha-masked materials (glTF MASK) in every pass that sees the scene: the G-buffer, the reflective shadow
// map and GPU ray casting cut the holes of the masked quad of tests/alpha_mask_scene.h (the shadow maps:
// tests/gl/setup_direct_test.cpp), and so do the techniques' own rays: `photon`'s photons and final
// gather, the k-buffer of global ray-bundles, micro-rendering's rays (its points: the surface sampler,
// tests/core/surface_points_test.cpp). Ray casting is held against Embree, whose filter function cuts the
// same holes in the path tracer (tests/ref/alpha_mask_test.cpp), and the techniques' light against its
// images.
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gl/frame/bindings.h"
#include "gl/frame/frame.h"
#include "gl/frame/ray_caster.h"
#include "gl/frame/rsm.h"
#include "gl/gl.h"
#include "ref/embree_scene.h"
#include "tests/alpha_mask_scene.h"
#include "tests/gl/gl_test_fixture.h"
#include "tests/gl/grb_harness.h"
#include "tests/gl/photon_test_scenes.h"
#include "tests/gl/point_test_util.h"

namespace bounce {
namespace {

// A 2 m floor at y = 0 under the masked quad (at 1.5 m), lit by the sun from straight above, seen from
// 3 m above looking down.
core::Scene floorUnderMask()
{
    core::Scene s;
    core::Material white;
    white.name = "floor";
    white.baseColor = glm::vec3(0.5f);
    white.specular = 0.0f;
    s.materials.push_back(white);
    core::Mesh f;
    f.name = "floor";
    f.positions = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
    f.normals.assign(4, glm::vec3(0, 1, 0));
    f.indices = {0, 1, 2, 0, 2, 3};
    s.meshes.push_back(f);
    testing::addMaskedQuad(s);
    // An opaque shelf under the hole after the masked mesh, so that the opaque meshes are two index ranges.
    core::Mesh shelf = f;
    shelf.name = "shelf";
    shelf.positions = {{-0.85f, 0.3f, -0.3f}, {-0.85f, 0.3f, 0.3f}, {-0.55f, 0.3f, 0.3f}, {-0.55f, 0.3f, -0.3f}};
    s.meshes.push_back(shelf);
    core::Light sun;
    sun.type = core::LightType::Directional;
    sun.direction = {0.0f, -1.0f, 0.0f};
    sun.intensity = glm::vec3(3.0f);
    s.lights.push_back(sun);
    s.camera.position = {0.0f, 3.0f, 0.0f};
    s.camera.forward = {0.0f, -1.0f, 0.0f};
    s.camera.up = {0.0f, 0.0f, -1.0f};
    s.camera.yfovRad = 2.0f * std::atan(1.0f / 3.0f); // the floor fills the image
    return s;
}

// Where a point lies under the quad: the transparent half (x < 0), the opaque half (x > 0), 5 cm or
// more from the quad's edges and its seam, or elsewhere.
enum class Under { Hole, Opaque, Elsewhere };
Under under(const glm::vec3& p)
{
    if (std::abs(p.z) > 0.45f || std::abs(p.x) < 0.05f || std::abs(p.x) > 0.45f) return Under::Elsewhere;
    return p.x < 0.0f ? Under::Hole : Under::Opaque;
}

// Whether a point at the shelf's height lies on it (inside: 5 cm from its edges) or near it.
bool onShelf(const glm::vec3& p, float margin)
{
    return p.x > -0.85f + margin && p.x < -0.55f - margin && std::abs(p.z) < 0.3f - margin;
}

class AlphaMaskTest : public GlTest {};

// Seen from above, the G-buffer holds the floor through the hole and the quad on its opaque half.
TEST_F(AlphaMaskTest, GBufferSeesThroughTheHoles)
{
    const core::Scene scene = floorUnderMask();
    constexpr int kSize = 48;
    gl::FrameSettings fs;
    fs.width = fs.height = kSize;
    fs.shadowMapSize = 64;
    gl::Frame frame(scene, fs);
    gl::PassTimers timers;
    frame.beginFrame();
    frame.renderGBuffer(timers);
    timers.endFrame(false);
    const core::Image position = frame.toImage(frame.readPositions()), normal = frame.toImage(frame.readNormals());
    int hole = 0, opaque = 0, shelf = 0, wrong = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec3 d = scene.camera.rayDirection(x + 0.5f, y + 0.5f, kSize, kSize);
            const auto at = [&](float height) { return scene.camera.position + d * ((3.0f - height) / -d.y); };
            const Under u = under(at(1.5f));
            if (u == Under::Elsewhere) continue;
            // Through the hole: the shelf, or the floor away from the shelf's edges.
            const bool toShelf = u == Under::Hole && onShelf(at(0.3f), 0.05f);
            if (u == Under::Hole && !toShelf && onShelf(at(0.3f), -0.05f)) continue;
            ++(toShelf ? shelf : u == Under::Hole ? hole : opaque);
            // All face the camera (the quad is double-sided), and none is the cleared background.
            const float want = toShelf ? 0.3f : u == Under::Hole ? 0.0f : 1.5f;
            if ((std::abs(position.at(x, y).y - want) > 1e-4f || normal.at(x, y).y < 0.99f) && wrong++ == 0)
                ADD_FAILURE() << "pixel " << x << ", " << y << " sees height " << position.at(x, y).y
                              << " with normal y " << normal.at(x, y).y << ", not height " << want;
        }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(hole, 100);
    EXPECT_GT(opaque, 100);
    EXPECT_GT(shelf, 20);
}

// The sun's RSM (an orthographic view from above) holds the floor through the hole: VPLs sit where
// light lands.
TEST_F(AlphaMaskTest, ReflectiveShadowMapSeesThroughTheHoles)
{
    const core::Scene scene = floorUnderMask();
    gl::FrameSettings fs;
    fs.width = fs.height = 16;
    fs.shadowMapSize = 64;
    gl::Frame frame(scene, fs);
    gl::RsmSettings rs;
    rs.size = 64;
    gl::RsmPass rsm(rs);
    gl::PassTimers timers;
    frame.beginFrame();
    rsm.render(frame, timers);
    timers.endFrame(false);
    ASSERT_EQ(rsm.viewCount(), 1);
    const std::vector<float> p = rsm.position().readFloats(0, 4);
    int hole = 0, opaque = 0, wrong = 0;
    for (std::size_t i = 0; i + 3 < p.size(); i += 4) {
        if (p[i + 3] == 0.0f) continue; // no geometry
        const glm::vec3 x(p[i], p[i + 1], p[i + 2]);
        const Under u = under(x);
        if (u == Under::Elsewhere) continue; // the shelf lies beside the quad, seen from the sun
        ++(u == Under::Hole ? hole : opaque);
        const float want = u == Under::Hole ? 0.0f : 1.5f;
        if (std::abs(x.y - want) > 1e-4f && wrong++ == 0)
            ADD_FAILURE() << "texel " << i / 4 << " holds height " << x.y << ", not " << want;
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(hole, 100);
    EXPECT_GT(opaque, 100);
}

// GPU ray casting with ALPHA_MASK finds what Embree with its filter finds: rays from above and below
// at random points and slants, away from the seam and the quad's edges (where the 512^2 resampled
// texture and the 4x4 original may round a hit either way).
TEST_F(AlphaMaskTest, GpuRayCastingCutsTheHolesLikeEmbree)
{
    const core::Scene scene = floorUnderMask();
    const gl::RayCaster caster(scene);
    ASSERT_EQ(caster.defines().size(), 1u); // ALPHA_MASK
    const gl::GpuScene gpu(scene);
    gpu.materials().bindBase(GL_SHADER_STORAGE_BUFFER, SSBO_MATERIALS);
    gpu.bindGeometry();
    gl::RayBatch batch(caster.defines());
    const ref::EmbreeScene embree(scene);

    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-0.9f, 0.9f), slant(-0.3f, 0.3f);
    std::vector<gl::BatchRay> rays;
    while (rays.size() < 2000) {
        const glm::vec3 at(u(rng), 1.5f, u(rng)); // where the ray crosses the quad's plane
        const bool fromAbove = rays.size() % 2 == 0;
        const glm::vec3 dir = glm::normalize(glm::vec3(slant(rng), fromAbove ? -1.0f : 1.0f, slant(rng)));
        const glm::vec3 origin = at - dir * 1.0f; // 1 m before the plane (above, or between floor and quad)
        const bool nearEdge = std::abs(at.x) < 0.01f || std::abs(std::abs(at.x) - 0.5f) < 0.01f ||
                              std::abs(std::abs(at.z) - 0.5f) < 0.01f;
        if (!nearEdge) rays.push_back({origin, 0.0f, dir, 10.0f});
    }
    int holes = 0, quadHits = 0;
    for (gl::RayStage stage : {gl::RayStage::Compute, gl::RayStage::Fragment}) {
        const std::vector<gl::BatchResult> got = batch.run(caster, rays, stage);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            ref::Hit hit;
            std::uint64_t count = 0;
            const bool e = embree.intersect(rays[i].origin, rays[i].dir, rays[i].tMin, rays[i].tMax, hit, count);
            const std::uint32_t want = e ? embree.globalTriangle(hit.mesh, hit.prim) : 0xFFFFFFFFu;
            ASSERT_EQ(got[i].triangle, want)
                << "ray " << i << (stage == gl::RayStage::Compute ? " (compute)" : " (fragment)");
            const bool occluded = embree.occluded(rays[i].origin, rays[i].dir, rays[i].tMin, rays[i].tMax, count);
            ASSERT_EQ(got[i].any != 0u, occluded) << "ray " << i;
            const glm::vec3 at = rays[i].origin + rays[i].dir * ((1.5f - rays[i].origin.y) / rays[i].dir.y);
            if (std::abs(at.x) < 0.5f && std::abs(at.z) < 0.5f) ++(want == 2u || want == 3u ? quadHits : holes);
        }
    }
    // Both kinds of crossing were tried: through a hole (on to the floor, or out) and onto the mask.
    EXPECT_GT(holes, 200);
    EXPECT_GT(quadHits, 200);
}

// Photons pass through the mask's holes as the path tracer's rays do: the sun's photons reach the floor
// through the transparent half, bounce, and those that go up through it leave the scene, so no photon
// lies in a hole, while the opaque half's underside, which the floor's light reaches, holds photons.
// (Traced as if the mask were opaque: 903 of the 2,934 photons stored lay in the hole.)
TEST_F(AlphaMaskTest, PhotonsPassThroughTheHoles)
{
    photontest::TracedPhotons traced(floorUnderMask(), photontest::photonPaths(32768));
    int hole = 0, opaque = 0;
    for (const gl::GpuPhoton& p : traced.tracer.downloadPhotons()) {
        const glm::vec3 x(p.positionPath);
        if (std::abs(x.y - testing::kMaskQuadHeight) > 1e-3f) continue;
        const Under u = under(x);
        hole += u == Under::Hole;
        opaque += u == Under::Opaque;
    }
    std::printf("[ measured ] %u photons stored: %d in the hole, %d under the opaque half\n",
                traced.tracer.storedCount(), hole, opaque);
    EXPECT_EQ(hole, 0);
    EXPECT_GT(opaque, 100);
}

// A global ray-bundle's rays pass through the mask's holes: captured along slanted directions from above
// and below, no k-buffer entry is an atlas texel in the hole, while the opaque half is hit. (Captured as
// if the mask were opaque, 278 entries lay in the hole.)
TEST_F(AlphaMaskTest, RayBundlesPassThroughTheHoles)
{
    gl::KBufferSettings ks = grbtest::kbufferSettings(gl::KBufferCapture::Atomic, 64, 8);
    ks.alphaMask = true;
    grbtest::Harness h(floorUnderMask(), ks, 32.0f);
    const std::vector<grbtest::Texel> texels = h.texels();
    int hole = 0, opaque = 0;
    for (const glm::vec3 dir : {glm::vec3(0.2f, -1.0f, 0.1f), glm::vec3(-0.1f, 1.0f, 0.3f)}) {
        h.kbuffer().capture(h.frame(), h.atlas(), h.view(glm::normalize(dir)), h.timers());
        for (const auto& pixel : h.kbuffer().readBack())
            for (const auto& [depth, texel] : pixel.entries) {
                const glm::vec3 x = texels[texel].position;
                if (std::abs(x.y - testing::kMaskQuadHeight) > 1e-3f) continue;
                hole += under(x) == Under::Hole;
                opaque += under(x) == Under::Opaque;
            }
        h.timers().endFrame(false);
    }
    std::printf("[ measured ] k-buffer entries on the quad: %d in the hole, %d on the opaque half\n", hole, opaque);
    EXPECT_EQ(hole, 0);
    EXPECT_GT(opaque, 200);
}

// A point light between the floor and the half-masked quad lights the floor and the quad's underside,
// whose opaque half sends light back down; seen from under the quad, looking down.
core::Scene floorLitUnderMask()
{
    core::Scene scene = floorUnderMask();
    scene.lights = {core::Light{.name = "lamp", .position = {0.0f, 1.0f, 0.0f}}}; // a point light of 1 W/sr
    scene.camera.position = {0.0f, 1.3f, 0.0f};
    scene.camera.yfovRad = 2.0f * std::atan(0.9f / 1.3f);
    return scene;
}

// A technique's indirect light on the floor of floorLitUnderMask() against the path tracer's one bounce,
// which cuts the same holes: the mean ratio under the transparent half, then under the opaque half. The
// image's left half looks at the floor under the hole (x < 0), its right half under the opaque half; the
// border, the columns about the seam and the shelf's (left of 4) are left out.
std::array<double, 2> floorRatios(const std::string& technique, const testing::Sets& sets)
{
    constexpr int size = 24;
    const core::Scene scene = floorLitUnderMask();
    const core::Image want = testing::pathTracedOneBounce(scene, size, size, 4096);
    const testing::PointRender got = testing::renderPoints(scene, technique, sets, size, size);
    std::array<double, 2> ratios{};
    for (const bool holeSide : {true, false}) {
        std::vector<bool> mask(std::size_t(size) * size, false);
        for (int y = 2; y < size - 2; ++y)
            for (int x = 4; x < size - 2; ++x)
                if (holeSide ? x < size / 2 - 2 : x >= size / 2 + 2) mask[std::size_t(y) * size + x] = true;
        const testing::Versus v = testing::versus(got.indirect, want, mask);
        std::printf("[ vs ref   ] %s, the floor under the %s half: mean ratio %.4f, relative RMSE %.4f\n",
                    technique.c_str(), holeSide ? "transparent" : "opaque", v.meanRatio, v.relRmse);
        ratios[holeSide ? 0 : 1] = v.meanRatio;
    }
    return ratios;
}

// Micro-rendering's rays pass through the holes, and its points leave them. Measured mean ratios: 1.145
// under the hole (the opaque half's nodes dilate into the black sky beside the seam), 1.018 under the
// opaque half; with the rays meeting the holes 2.405 and 1.788, with points in the holes 1.622 and 1.390.
TEST_F(AlphaMaskTest, MicroRenderingSeesThroughTheHoles)
{
    const std::array<double, 2> r = floorRatios("microrender", {{"coarsestLevel", "0"}});
    EXPECT_GT(r[0], 0.85);
    EXPECT_LT(r[0], 1.25);
    EXPECT_GT(r[1], 0.9);
    EXPECT_LT(r[1], 1.1);
}

// The photon final gather's rays pass through the holes (the photons: PhotonsPassThroughTheHoles). Measured
// mean ratios (its light is every bounce's, the reference's one bounce's): 1.006 under the hole, 1.009 under
// the opaque half; with the gather's rays meeting the holes 2.265 and 1.782.
TEST_F(AlphaMaskTest, PhotonGatherSeesThroughTheHoles)
{
    const std::array<double, 2> r = floorRatios("photon", {});
    for (double ratio : r) {
        EXPECT_GT(ratio, 0.85);
        EXPECT_LT(ratio, 1.15);
    }
}

} // namespace
} // namespace bounce
