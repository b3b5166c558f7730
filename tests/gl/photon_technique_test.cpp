// The `photon` technique as a whole (gl/technique/photon/): its interpolation reproduces a constant field
// exactly and a shading point on its sample takes that sample's value; its image against the path
// tracer's `full` on the three Cornell variants (and the direct light alone clearly further); the caustic
// map against a plane mirror's closed form; and the hard cases of the issue: the light 1 mm under the
// ceiling, the scene at 1000 times the scale, gather hits that no cut node covers, corners, and the same
// frame giving the same image. Tiny images (llvmpipe).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <gtest/gtest.h>

#include "core/brdf.h"
#include "core/cornell.h"
#include "core/metrics.h"
#include "gl/frame/frame.h"
#include "gl/frame/ray_caster.h"
#include "gl/renderer.h"
#include "gl/technique/photon/final_gather.h"
#include "gl/technique/photon/photon_tracer.h"
#include "gl/technique/photon/photon_tree.h"
#include "gl/technique/photon/shading_clusters.h"
#include "ref/reference.h"
#include "tests/gl/gl_test_fixture.h"
#include "tests/gl/moved_scene.h"
#include "tests/gl/photon_test_scenes.h"
#include "tests/image_expect.h"

namespace bounce {
namespace {

constexpr int kSize = 32; // reference pixels per side
constexpr int kSuper = 2; // GL pixels per reference pixel side (box-averaged, as the path tracer's pixels)

// What the tests render with: fewer photons, clusters and rays than the defaults, for llvmpipe.
gl::ParamValues testValues(const std::vector<std::pair<std::string, double>>& extra = {})
{
    const gl::TechniqueInfo& info = gl::findTechnique("photon");
    gl::ParamValues v(info.params);
    v.setValue("photons", 32768);
    v.setValue("clusters", 300);
    v.setValue("gatherRays", 128);
    for (const auto& [k, x] : extra) v.setValue(k, x);
    return v;
}

gl::ParamValues frameValues()
{
    gl::ParamValues f(gl::frameParams());
    f.setValue("shadow.size", 512);
    return f;
}

struct Rendered {
    core::Image image, indirect, emission, diffuse;
    std::vector<gl::Counter> counters;
};

Rendered render(const core::Scene& scene, int w, int h, const gl::ParamValues& values,
                const std::string& technique = "photon")
{
    gl::Renderer r(scene, technique, frameValues(), values, w, h);
    r.renderFrame(false);
    Rendered out;
    out.image = r.image();
    out.indirect = r.frame().read(r.frame().indirect());
    out.emission = r.frame().readEmission();
    out.diffuse = r.frame().read(r.frame().diffuse());
    out.counters = r.counters();
    return out;
}

double counter(const Rendered& r, const std::string& name)
{
    for (const gl::Counter& c : r.counters)
        if (c.name == name) return c.value;
    return NAN;
}

bool allFiniteNonNegative(const core::Image& img)
{
    return std::all_of(img.rgb.begin(), img.rgb.end(), [](float v) { return std::isfinite(v) && v >= 0.0f; });
}

core::Image reference(const core::Scene& scene, int spp = 65536, ref::LightPaths paths = ref::LightPaths::Full)
{
    ref::RenderSettings s;
    s.paths = paths;
    s.width = kSize;
    s.height = kSize;
    s.targetNoise = 0.02;
    s.spp = spp;
    s.seed = 11;
    s.progress = false;
    return ref::cachedReference(scene, scene.camera, s).image;
}

// Reference pixels that see an emitter (and their neighbours) are left out, as in the bench.
std::vector<bool> notEmitters(const core::Image& emission)
{
    const core::Image e = core::boxDownsample(emission, kSize, kSize);
    std::vector<bool> keep(std::size_t(kSize) * kSize, true);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec3 v = e.at(x, y);
            if (std::max({v.x, v.y, v.z}) <= 0.0f) continue;
            for (int j = std::max(y - 1, 0); j <= std::min(y + 1, kSize - 1); ++j)
                for (int i = std::max(x - 1, 0); i <= std::min(x + 1, kSize - 1); ++i)
                    keep[std::size_t(j) * kSize + i] = false;
        }
    return keep;
}

class PhotonTechniqueTest : public GlTest {};

// Interpolation alone, in both of the pass's forms (a full-screen triangle, a compute pass: the same
// arithmetic): every sample carries the same irradiance: every shading point reads exactly it
// (E_own + sum w (E_j - E_own) / sum w); then every sample a different one: each sample's own pixel reads
// exactly its sample's value (w singular there), and the two forms give the same image.
TEST_F(PhotonTechniqueTest, InterpolationReproducesAConstantFieldExactly)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    constexpr int w = 41, h = 30; // odd: the compute form's partial work groups
    photontest::ClusteredFrame cf(scene, w, h, 60);
    gl::Frame& frame = cf.frame;
    gl::PassTimers& timers = cf.timers;
    gl::Buffer& counters = cf.counters;
    gl::ShadingClusters& clusters = cf.clusters;
    const std::vector<gl::GpuCluster> original = clusters.download();
    const std::vector<float> pos = frame.readPositions();
    core::Image fields[2];
    for (bool asCompute : {false, true}) {
        SCOPED_TRACE(asCompute ? "compute" : "fragments");
        std::vector<gl::GpuCluster> c = original;
        const glm::vec3 constant(0.3f, 0.7f, 1.9f);
        for (gl::GpuCluster& k : c) k.irradiance = glm::vec4(constant, 0.25f);
        clusters.clusters().update(0, c.size() * sizeof(gl::GpuCluster), c.data());
        clusters.buildPointTree(true, counters);
        gl::Interpolation interpolation(asCompute);
        frame.clearIndirect();
        interpolation.run(frame, clusters, 10.0f, false, timers, true);
        const core::Image e = frame.read(frame.indirect());
        int off = 0, valid = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                if (pos[(std::size_t(h - 1 - y) * w + x) * 4 + 3] == 0.0f) continue;
                ++valid;
                off += e.at(x, y) != constant;
            }
        EXPECT_GT(valid, 600);
        EXPECT_EQ(off, 0) << "shading points whose interpolated constant is not the constant";

        for (std::size_t k = 0; k < c.size(); ++k) c[k].irradiance = glm::vec4(float(k), float(2 * k), 1.0f, 0.25f);
        clusters.clusters().update(0, c.size() * sizeof(gl::GpuCluster), c.data());
        clusters.buildPointTree(true, counters);
        frame.clearIndirect();
        interpolation.run(frame, clusters, 10.0f, false, timers, true);
        const core::Image f = frame.read(frame.indirect());
        int wrong = 0, samples = 0;
        for (std::size_t k = 0; k < c.size(); ++k) {
            if (c[k].sample.w < 0.0f) continue;
            ++samples;
            const int p = int(c[k].sample.w), x = p % w, y = h - 1 - p / w;
            wrong += f.at(x, y) != glm::vec3(float(k), float(2 * k), 1.0f);
        }
        EXPECT_GT(samples, 30);
        EXPECT_EQ(wrong, 0) << "samples whose own pixel does not read their irradiance";
        fields[asCompute ? 1 : 0] = f;
    }
    testing::expectImagesClose("photon-interpolation-compute-vs-fragments", fields[1], fields[0],
                               testing::ImageMetric::relativeRmse(), 1e-6, "one function, two stages");
}

struct Variant {
    const char* scene;
    double tolerance; // relative RMSE against `full`, emitters left out
};

class PhotonPathTracerTest : public PhotonTechniqueTest, public ::testing::WithParamInterface<Variant> {};

// Against the path tracer's `full` at 32 x 32 (GL at 64 x 64, box-averaged): the error is what 300
// clusters, a cut, 32k photons and pixel-centre edges leave; the direct light alone must be far off.
TEST_P(PhotonPathTracerTest, MatchesFull)
{
    const Variant v = GetParam();
    const core::Scene scene = core::makeCornell(v.scene);
    const core::Image want = reference(scene);
    const Rendered photon = render(scene, kSize * kSuper, kSize * kSuper, testValues());
    const Rendered direct = render(scene, kSize * kSuper, kSize * kSuper, gl::ParamValues(), "direct");
    const std::vector<bool> mask = notEmitters(photon.emission);
    const core::Image got = core::boxDownsample(photon.image, kSize, kSize);
    const double directError = testing::measureImages(core::boxDownsample(direct.image, kSize, kSize), want,
                                                      testing::ImageMetric::relativeRmse(), &mask);
    const double meanError = testing::measureImages(got, want, testing::ImageMetric::meanRelative(), &mask);
    const double error = testing::expectImagesClose(v.scene, got, want, testing::ImageMetric::relativeRmse(),
                                                    v.tolerance, "clusters, cut, photon noise and edges", &mask);
    std::printf("[ measured ] %s: relative RMSE %.4f (direct alone %.4f), mean off by %.4f, cut %g, clusters %g\n",
                v.scene, error, directError, meanError, counter(photon, "cut.size"), counter(photon, "clusters"));
    EXPECT_LT(meanError, 0.06) << "the indirect light's energy";
    EXPECT_GT(directError, 2.0 * error) << "the direct light alone must be clearly further from `full`";
}

INSTANTIATE_TEST_SUITE_P(Cornell, PhotonPathTracerTest,
                         // Measured 0.178, 0.080 and 0.122 (means within 0.7%, 1.4%, 1.1%); most of it on
                         // the edges of direct light and shadows (pixel centres against
                         // the path tracer's box filter: `direct` has the same there).
                         ::testing::Values(Variant{"cornell-spot", 0.25}, Variant{"cornell-point", 0.12},
                                           Variant{"cornell-area", 0.18}),
                         [](const ::testing::TestParamInfo<Variant>& p) {
                             std::string n = p.param.scene;
                             std::replace(n.begin(), n.end(), '-', '_');
                             return n;
                         });

// The glossy last bounce (photon_glossy.comp) on cornell-glossy: the technique's indirect light against the
// path tracer's `full` minus its `direct`, which leaves out the shadow edges of the direct light that every
// technique shares. Sampling the metal block's lobe must be clearly closer than reflecting the interpolated
// irradiance with the lobe's albedo (glossyRays=0), which loses the direction the light comes from.
// Measured over the block's 85 pixels (32 x 32): 0.317 sampled (4 rays per pixel), 0.720 with the albedo;
// 16 and 64 rays give 0.281 and 0.276, what the test's 32k photons, 300 clusters and 128 gather rays
// leave at the rays' hits.
TEST_F(PhotonTechniqueTest, GlossyLastBounceMatchesTheIndirectLight)
{
    const core::Scene scene = core::makeCornell("cornell-glossy");
    core::Image want = reference(scene);
    const core::Image direct = reference(scene, 65536, ref::LightPaths::Direct);
    for (std::size_t i = 0; i < want.rgb.size(); ++i) want.rgb[i] -= direct.rgb[i];
    double errors[2] = {0.0, 0.0};
    for (int rays : {0, 4}) {
        const Rendered r = render(scene, kSize * kSuper, kSize * kSuper, testValues({{"glossyRays", rays}}));
        EXPECT_TRUE(allFiniteNonNegative(r.indirect));
        // The block's pixels: no diffuse colour (a metal) and no emitter (the lamp has no albedo either).
        std::vector<bool> mask = notEmitters(r.emission);
        const core::Image diffuse = core::boxDownsample(r.diffuse, kSize, kSize);
        for (std::size_t i = 0; i < mask.size(); ++i)
            mask[i] = mask[i] && glm::length(diffuse.at(int(i) % kSize, int(i) / kSize)) == 0.0f;
        const core::Image got = core::boxDownsample(r.indirect, kSize, kSize);
        errors[rays > 0] = testing::measureImages(got, want, testing::ImageMetric::relativeRmse(), &mask);
        const double mean = testing::measureImages(got, want, testing::ImageMetric::meanRelative(), &mask);
        std::printf("[ measured ] cornell-glossy block's indirect, glossyRays=%d: relative RMSE %.4f, mean off by "
                    "%.4f over %d pixels\n",
                    rays, errors[rays > 0], mean, int(std::count(mask.begin(), mask.end(), true)));
    }
    EXPECT_LT(errors[1], 0.4) << "the lobe sampled at the block's pixels";
    EXPECT_LT(errors[1], 0.6 * errors[0]) << "sampling the lobe must beat its albedo";
}

// The caustic map's errors against the path tracer's `full` at kSize^2 (rendered at kSuper x kSuper and
// box-downsampled): relative RMSE and mean, without the map (index 0) and with it at `roughness` (1).
struct CausticErrors {
    double rmse[2] = {0.0, 0.0}, mean[2] = {0.0, 0.0};
};

CausticErrors causticErrors(const char* name, double roughness)
{
    const core::Scene scene = core::makeCornell(name);
    const core::Image want = reference(scene, 8192);
    CausticErrors e;
    for (int with = 0; with < 2; ++with) {
        const double r = with ? roughness : 0.0;
        const Rendered got = render(scene, kSize * kSuper, kSize * kSuper, testValues({{"causticRoughness", r}}));
        EXPECT_TRUE(allFiniteNonNegative(got.indirect));
        const std::vector<bool> mask = notEmitters(got.emission);
        const core::Image image = core::boxDownsample(got.image, kSize, kSize);
        e.rmse[with] = testing::measureImages(image, want, testing::ImageMetric::relativeRmse(), &mask);
        e.mean[with] = testing::measureImages(image, want, testing::ImageMetric::meanRelative(), &mask);
        std::printf("[ measured ] %s, causticRoughness=%g: relative RMSE %.4f, mean off by %.4f\n", name, r,
                    e.rmse[with], e.mean[with]);
    }
    return e;
}

// The caustic map on cornell-mirror (the tall block a polished metal): its caustics on the floor, the red
// wall and the ceiling are L S D paths, which the final gather can only find by its rays meeting the
// emitter's image in the block. With the caustic map (causticRoughness 0.1) the caustic photons are read
// at the pixels and the gather's rays pass on through the block; without it (0) the gather's hits on the
// block reflect the lights and the photons' mean direction through its narrow lobe. Against the path
// tracer's `full` at 32 x 32, the image with the map must be closer.
TEST_F(PhotonTechniqueTest, CausticMapBringsCornellMirrorCloser)
{
    const CausticErrors e = causticErrors("cornell-mirror", 0.1);
    EXPECT_LT(e.rmse[1], 0.25);
    EXPECT_LT(e.rmse[1], 0.5 * e.rmse[0]) << "the caustic map must bring the image closer";
    EXPECT_LT(e.mean[1], 0.03) << "the caustics' energy";
}

// The same on cornell-glossy (the tall block a rough metal, roughness 0.3): the block's glossy reflection
// of the light on the red wall and the floor comes from the caustic photons (causticRoughness 0.35, the
// default), and the gather's rays that meet the block pass on along a direction drawn from its lobe.
// Without the map the gather finds the block's highlight with few of its rays. Measured: relative RMSE
// 0.1814 and the mean 1.95% low without the map, 0.1624 and 0.11% with it (256 x 256 against `full` at
// 1024 samples, 4 x 4 blocks: 0.1244 and 0.0770).
TEST_F(PhotonTechniqueTest, CausticMapBringsCornellGlossyCloser)
{
    const CausticErrors e = causticErrors("cornell-glossy", 0.35);
    EXPECT_LT(e.rmse[1], e.rmse[0]) << "the glossy caustics must bring the image closer";
    EXPECT_LT(e.mean[1], 0.01) << "the glossy caustics' energy";
}

// A plane mirror on a Lambertian floor (albedo 0.5), a spot aimed at the mirror: the caustic map against
// its closed form. The mirror (x = 0, facing +x) is a polished metal (F0 0.9, roughness 0: GGX alpha 1e-3),
// so every photon the floor stores after it is a caustic photon, and the caustic at a floor point x is the
// light of the spot's mirror image L': E = I w F h / d^3, with d = |x - L'|, h the image's height, F the
// Schlick Fresnel term at the mirror's angle of incidence and w the spot's falloff along the path. The
// caustic pass alone writes into the cleared indirect texture, which must hold rho / pi E: compared on 4 x 4
// pixel blocks of the floor away from its edges (0.2 <= x <= 1.6, |z| <= 0.8, where E spans 14 x).
// Measured: relative RMSE 0.032, the mean 0.9999 of the closed form's (a hard cone of 0.6 rad: 0.023 and
// 0.9998); 0.635 when a soft spot's photons held its falloff twice (photon_tracer.cpp), 1/3 of it without
// the cone filter's normalisation.
TEST_F(PhotonTechniqueTest, CausticOfAPlaneMirrorIsTheMirroredSpot)
{
    constexpr float rho = 0.5f;
    core::Scene scene;
    scene.name = "plane mirror";
    core::Material floor, mirror;
    floor.baseColor = glm::vec3(rho);
    floor.specular = 0.0f;
    mirror.baseColor = glm::vec3(0.9f);
    mirror.metallic = 1.0f;
    mirror.roughness = 0.0f;
    scene.materials = {floor, mirror};
    core::Mesh floorMesh, mirrorMesh;
    testing::addQuad(floorMesh, {0, 0, -1}, {0, 0, 1}, {2, 0, 1}, {2, 0, -1});
    testing::addQuad(mirrorMesh, {0, 0, -1}, {0, 1, -1}, {0, 1, 1}, {0, 0, 1});
    mirrorMesh.material = 1;
    scene.meshes = {floorMesh, mirrorMesh};
    core::Light spot;
    spot.type = core::LightType::Spot;
    spot.position = {0.6f, 0.6f, 0.0f};
    spot.direction = glm::normalize(glm::vec3(-1.0f, -0.5f, 0.0f));
    spot.innerConeRad = 0.4f;
    spot.outerConeRad = 0.6f;
    scene.lights = {spot};
    scene.camera.position = {1.0f, 2.2f, 0.0f};
    scene.camera.forward = {0.0f, -1.0f, 0.0f};
    scene.camera.up = {1.0f, 0.0f, 0.0f};
    scene.camera.yfovRad = 0.9f;

    constexpr int size = 64;
    gl::Frame frame(scene, photontest::smallFrame(size, size));
    gl::PassTimers timers;
    frame.beginFrame();
    frame.renderGBuffer(timers);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    frame.indirect().clear(0, zero);
    gl::Buffer counters("photon.counters", gl::kCounterSlots * 4);
    gl::PhotonTracerSettings ts;
    ts.photons = 262144;
    gl::PhotonTracer tracer(ts);
    tracer.trace(frame, frame.rayCaster(), counters, timers);
    gl::PhotonTree tree;
    tree.build(tracer.photons(), tracer.storedCount(), tracer.sceneSize() / 4096.0f, timers);
    gl::CausticMap caustic(frame, ts.causticRoughness, 0.01f);
    ASSERT_TRUE(caustic.active());
    caustic.run(frame, tree, tracer.photons(), tracer.sceneSize(), timers);
    const core::Image got = frame.read(frame.indirect());
    ASSERT_TRUE(allFiniteNonNegative(got));

    const glm::dvec3 image(-spot.position.x, spot.position.y, spot.position.z); // L'
    const glm::vec3 f0 = core::BrdfParams::fromMaterial(mirror).f0;
    constexpr int block = 4;
    double sumSquares = 0.0, sumWant = 0.0, sumGot = 0.0;
    int blocks = 0;
    for (int by = 0; by < size; by += block)
        for (int bx = 0; bx < size; bx += block) {
            glm::dvec3 want(0.0), have(0.0);
            bool inside = true;
            for (int y = by; y < by + block; ++y)
                for (int x = bx; x < bx + block; ++x) {
                    const glm::dvec3 dir(scene.camera.rayDirection(x + 0.5f, y + 0.5f, size, size));
                    const glm::dvec3 p =
                        glm::dvec3(scene.camera.position) - dir * (double(scene.camera.position.y) / dir.y);
                    inside = inside && p.x >= 0.2 && p.x <= 1.6 && std::abs(p.z) <= 0.8;
                    const glm::dvec3 d = p - image;
                    const double dist = glm::length(d);
                    const glm::dvec3 u = d / dist;
                    const double w =
                        spot.spotWeight(float(glm::dot(glm::dvec3(-u.x, u.y, u.z), glm::dvec3(spot.direction))));
                    const glm::dvec3 f(core::fresnelSchlick(f0, float(u.x)));
                    want +=
                        glm::dvec3(spot.intensity) * w * f * (image.y / dist) / (dist * dist) * double(rho / core::kPi);
                    have += glm::dvec3(got.at(x, y));
                }
            if (!inside) continue;
            const double a = core::luminance(glm::vec3(have)), b = core::luminance(glm::vec3(want));
            sumSquares += (a - b) * (a - b) / (b * b);
            sumWant += b;
            sumGot += a;
            ++blocks;
        }
    ASSERT_GT(blocks, 40);
    const double error = std::sqrt(sumSquares / blocks), mean = sumGot / sumWant;
    std::printf("[ measured ] plane mirror's caustic, %d blocks: relative RMSE %.4f, mean %.4f of the closed form's "
                "(%u photons stored)\n",
                blocks, error, mean, tracer.storedCount());
    EXPECT_LT(error, 0.1);
    EXPECT_NEAR(mean, 1.0, 0.03);
}

// Gathering at every pixel makes a cluster of each, and a 300 x 300 viewport has 90,000: more work groups
// than the 65,535 a driver may allow on one axis of a dispatch (the gather's one group per cluster). Every
// cluster must still gather: the image's mean indirect light must be that of a 200 x 200 view (40,000
// clusters, one axis) of the same scene. Measured 0.01640 and 0.01652; no indirect light at all when the
// gather was one dispatch of 90,000 groups (GL_INVALID_VALUE: `gatherAt=pixels` at 256 x 256 was 0.90 from
// `full`), 0.0093 when the groups past the first 65,535 gathered for the first clusters again.
TEST_F(PhotonTechniqueTest, MorePixelClustersThanOneDispatchAxisHolds)
{
    gl::ParamValues v = testValues({{"photons", 4096}, {"gatherRays", 4}});
    v.set(gl::findTechnique("photon").params, "gatherAt", "pixels");
    const core::Scene scene = core::makeCornell("cornell-spot");
    const Rendered big = render(scene, 300, 300, v), small = render(scene, 200, 200, v);
    ASSERT_GT(counter(big, "clusters"), 65535.0);
    EXPECT_TRUE(allFiniteNonNegative(big.indirect));
    const auto mean = [](const core::Image& img) {
        double sum = 0.0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) sum += core::luminance(img.at(x, y));
        return sum / (double(img.width) * img.height);
    };
    const double a = mean(big.indirect), b = mean(small.indirect);
    std::printf("[ measured ] mean indirect luminance: %.5g with %g pixel clusters, %.5g with %g\n", a,
                counter(big, "clusters"), b, counter(small, "clusters"));
    EXPECT_NEAR(a / b, 1.0, 0.05);
}

// The point light 1 mm under the ceiling: half its power lands within millimetres of it, and that spot
// lights the room like a small, very bright lamp. Gather rays find it rarely and bring back a lot: the
// final gather stays unbiased but its noise is heavy-tailed there: with 64 rays most clusters miss the spot
// (the image 22% too dark on average), with 1024 a few catch it and come out far too bright (relative RMSE
// 2.17 here, the mean within 7%). What must hold: every value finite and non-negative, the error bounded, and
// the overall energy converging to the ground truth's as the gather takes more rays. The bound is on the
// tail, not on a typical value: over 14 cluster counts from 280 to 319 (1024 rays) the relative RMSE ran
// from 0.60 to 3.31, the same spread before and after the G-buffer stopped storing positions (2 of 14
// above 1.5 in both); which clusters catch the spot moves with any ulp of their positions.
// Measured below the ceiling (the top quarter of the image), whose hot spot is direct light that pixel
// centres and the path tracer's box filter see differently (relative RMSE 7.8 with it, in every technique).
TEST_F(PhotonTechniqueTest, LightUnderTheCeilingStaysFiniteAndConverges)
{
    const core::Scene scene = core::makeCornell("cornell-point-ceiling");
    // 16384 samples per pixel, not 65536: the lamp's hot spot keeps this reference's noise far above the 2%
    // it asks for (23% at 16384, 16.6% at 65536), so the sample count alone decides its time. At 65536 this
    // was the suite's longest test (about 70 s in a full run). The test's figures are a mean over 768 pixels
    // (23% / sqrt(768): under 1%) and a bound of 4 on the relative RMSE. Measured with it: the mean 25.0% off
    // with 64 rays, 3.5% with 1024 (3.0% against the 65536-sample reference); 25.1% and 5.0% with the
    // interpolation's error bound at 0.2, not 0.3.
    const core::Image want = reference(scene, 16384);
    std::vector<bool> belowCeiling(std::size_t(kSize) * kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) belowCeiling[std::size_t(y) * kSize + x] = y >= kSize / 4;
    double previous = 0.0;
    for (int rays : {64, 1024}) {
        SCOPED_TRACE(std::to_string(rays) + " rays");
        const Rendered r = render(scene, kSize * kSuper, kSize * kSuper, testValues({{"gatherRays", rays}}));
        EXPECT_TRUE(allFiniteNonNegative(r.indirect));
        const core::Image got = core::boxDownsample(r.image, kSize, kSize);
        const double meanError = testing::measureImages(got, want, testing::ImageMetric::meanRelative(), &belowCeiling);
        const double error = testing::measureImages(got, want, testing::ImageMetric::relativeRmse(), &belowCeiling);
        std::printf("[ measured ] cornell-point-ceiling, %d gather rays: relative RMSE %.4f, mean off by %.4f\n", rays,
                    error, meanError);
        EXPECT_LT(error, 4.0);
        if (previous > 0.0) {
            EXPECT_LT(meanError, 0.1);
            EXPECT_LT(meanError, 0.5 * previous) << "16 times the rays must bring the energy closer";
        }
        previous = meanError;
    }
}

// Eq. 2's alpha is per scene size, the ray offsets, the tree's smallest radius and R_j's bounds are
// fractions of it, Morton codes span the scene's box: the same scene at 1000 times the scale (the area
// light's radiance unchanged: the image is the same) gives the same indirect light, up to float rounding.
// Rounding moves a few cluster centres, and a moved cluster gathers at another sample with its own ray
// noise (128 rays): measured 0.063 relative RMSE, in cluster-shaped patches. The clusters themselves are
// compared in photon_clusters_test.cpp (AlphaIsPerSceneSize).
TEST_F(PhotonTechniqueTest, SceneScaledByAThousandGivesTheSameImage)
{
    const core::Scene scene = core::makeCornell("cornell-area");
    const core::Scene big = photontest::scaledScene(scene, 1000.0f);
    const Rendered a = render(scene, 48, 48, testValues({{"temporal", 0}}));
    const Rendered b = render(big, 48, 48, testValues({{"temporal", 0}}));
    const double error =
        testing::expectImagesClose("scaled", b.indirect, a.indirect, testing::ImageMetric::relativeRmse(), 0.1,
                                   "clusters moved by rounding gather their own noise");
    std::printf("[ measured ] scaled by 1000: indirect relative RMSE %.3g; clusters %g and %g, cut %g and %g\n", error,
                counter(a, "clusters"), counter(b, "clusters"), counter(a, "cut.size"), counter(b, "cut.size"));
}

// Deforming geometry (Frame::moveVertices): photons are traced, and the final gather's rays cast, through the
// frame's BVH (Frame::rayCaster), which follows the moved scene. cornell-spot stretched by 1.3 along x after a
// first frame against the stretched box loaded as it is: the same light, up to the shading clusters, which
// start from the first frame's seeds on one side and from none on the other. Measured (indirect light, one
// against the other): relative RMSE 0.116, means 0.5% apart; with the BVH of the box as loaded (photons hit
// the old walls and are shaded at the moved ones), 0.609 and 40%.
TEST_F(PhotonTechniqueTest, DeformedSceneIsLitAsTheDeformedSceneLoaded)
{
    constexpr int size = 32;
    const testing::StretchedScene st = testing::stretchedScene(core::makeCornell("cornell-spot"), {1.3f, 1.0f, 1.0f});
    const core::Scene &scene = st.scene, &stretched = st.stretched;
    const testing::MovedVertices& moved = st.moved;
    gl::Renderer r(scene, "photon", frameValues(), testValues(), size, size);
    r.renderFrame(false);
    ASSERT_TRUE(r.moveVertices(moved.positions, moved.normals));
    r.renderFrame(false);
    const core::Image deformed = r.frame().read(r.frame().indirect());
    const Rendered fresh = render(stretched, size, size, testValues());
    ASSERT_TRUE(allFiniteNonNegative(deformed));
    const double rmse = testing::measureImages(deformed, fresh.indirect, testing::ImageMetric::relativeRmse());
    const double mean = testing::measureImages(deformed, fresh.indirect, testing::ImageMetric::meanRelative());
    std::printf("[ deformed ] against the stretched box loaded: relative RMSE %.4f, means off by %.4f\n", rmse, mean);
    EXPECT_LT(rmse, 0.25);
    EXPECT_LT(std::abs(mean), 0.03);
}

// Few photons: a sparse cut leaves gather hits that no kernel reaches (the fallback's wider kernels
// take them, or nothing does); the counters say how many, the image stays finite and non-negative.
TEST_F(PhotonTechniqueTest, GatherHitsNoCutNodeCovers)
{
    const Rendered r = render(core::makeCornell("cornell-spot"), 32, 32,
                              testValues({{"photons", 64}, {"leafPhotons", 1}, {"clusters", 50}}));
    const double fallback = counter(r, "gather.fallbackHits"), uncovered = counter(r, "gather.uncoveredHits");
    std::printf("[ measured ] 64 photons: %g gather hits by the fallback kernels, %g by none, of %g\n", fallback,
                uncovered, counter(r, "gather.rays"));
    EXPECT_GT(fallback + uncovered, 0.0);
    EXPECT_TRUE(allFiniteNonNegative(r.indirect));
}

// Corners: shading points where walls meet take no light from cut nodes or samples on the other wall
// (max(0, n_j . n_y) and Ward's normal term); the corner pixels of cornell-spot stay finite,
// non-negative, and within a factor of two of the ground truth on average.
TEST_F(PhotonTechniqueTest, CornersStayNearTheGroundTruth)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    const Rendered r = render(scene, kSize * kSuper, kSize * kSuper, testValues());
    EXPECT_TRUE(allFiniteNonNegative(r.indirect));
    const core::Image want = reference(scene), got = core::boxDownsample(r.image, kSize, kSize);
    // The back wall's corners and the edges where it meets the side walls, floor and ceiling.
    std::vector<bool> corners(std::size_t(kSize) * kSize, false);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const bool nearSide = x == 7 || x == 8 || x == 23 || x == 24;
            const bool nearEnd = y == 7 || y == 8 || y == 23 || y == 24;
            corners[std::size_t(y) * kSize + x] = nearSide || nearEnd;
        }
    const double mean = testing::measureImages(got, want, testing::ImageMetric::meanRelative(), &corners);
    std::printf("[ measured ] corner and edge pixels: mean off by %.4f\n", mean);
    EXPECT_LT(mean, 0.5);
}

// Fig. 6's reference for the cut, gathering in the full photon map, against the cut at every pixel: the
// same photons give about the same image (measured: means 0.0313 against 0.0322). It once came out 57%
// darker: brdfEval(wi = n) took pow(1 - cos, 5) of a cosine rounded above 1, a NaN on llvmpipe.
TEST_F(PhotonTechniqueTest, FullPhotonMapAgreesWithTheCut)
{
    const core::Scene scene = core::makeCornell("cornell-spot");
    const auto values = [](const char* density) {
        gl::ParamValues v = testValues({{"gatherRays", 32}});
        v.set(gl::findTechnique("photon").params, "gatherAt", "pixels");
        v.set(gl::findTechnique("photon").params, "density", density);
        return v;
    };
    const Rendered cut = render(scene, 32, 32, values("cut")), photons = render(scene, 32, 32, values("photons"));
    EXPECT_TRUE(allFiniteNonNegative(photons.indirect));
    testing::expectImagesClose("full photon map", photons.image, cut.image, testing::ImageMetric::meanRelative(), 0.08,
                               "the cut's kernels against density estimates at the hits");
}

// The same frame twice, in two renderers: the same image, bit for bit (no float atomics).
TEST_F(PhotonTechniqueTest, SameFrameGivesTheSameImage)
{
    const core::Scene scene = core::makeCornell("cornell-point");
    const gl::ParamValues v = testValues({{"photons", 8192}, {"gatherRays", 32}});
    const Rendered a = render(scene, 24, 24, v), b = render(scene, 24, 24, v);
    ASSERT_EQ(a.indirect.rgb.size(), b.indirect.rgb.size());
    EXPECT_EQ(std::memcmp(a.indirect.rgb.data(), b.indirect.rgb.data(), a.indirect.rgb.size() * sizeof(float)), 0);
}

} // namespace
} // namespace bounce
