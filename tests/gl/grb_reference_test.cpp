// `grb` against the path tracer's `full` light paths (ref/) on the Cornell variants: the frame's direct
// light plus the ray bundles' indirect light must meet the ground truth of every path length. Small
// sizes (32^2 pixels, a 96^2 k-buffer, an atlas of 8192 texels, 192 directions) keep it to seconds on
// llvmpipe; the references (1024 samples per pixel) come from the shared cache when present. Also: the
// bundles' own direct light of an emitter, and one bounce's glossy paths under a spot.
//
// Figures, over the pixels that do not see an emitter (emission is the G-buffer's, exact, and its
// edges alias against the box-filtered reference):
//   - the mean indirect light (full - direct of the path tracer, against grb's indirect texture): the
//     energy the bundles move, what a missing or doubled bounce changes by tens of per cent;
//   - the relative RMSE of the whole image against `full`, with `direct` alone as the negative control.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/image.h"
#include "core/metrics.h"
#include "gl/renderer.h"
#include "ref/reference.h"
#include "tests/gl/gl_test_fixture.h"

namespace bounce {
namespace {

constexpr int kSize = 32;
constexpr int kDirections = 192;

core::Image reference(const core::Scene& scene, ref::LightPaths paths)
{
    ref::RenderSettings s;
    s.paths = paths;
    s.width = s.height = kSize;
    s.spp = 1024;
    s.seed = 11;
    s.progress = false;
    return ref::cachedReference(scene, scene.camera, s).image;
}

struct Rendered {
    core::Image image, indirect, emission;
};

Rendered render(const core::Scene& scene, const std::string& technique,
                const std::vector<std::string>& grbSets = {"emitters=frame"}, int directions = kDirections)
{
    const gl::TechniqueInfo& info = gl::findTechnique(technique);
    gl::ParamValues f(gl::frameParams()), t(info.params);
    f.setValue("shadow.size", 512);
    if (technique == "grb") {
        t.set(info.params, "kbufferSize", "96");
        t.set(info.params, "atlasTexels", "8192");
        t.set(info.params, "directionsPerFrame", "16");
        for (const std::string& kv : grbSets) {
            const std::size_t eq = kv.find('=');
            t.set(info.params, kv.substr(0, eq), kv.substr(eq + 1));
        }
    }
    gl::Renderer r(scene, technique, f, t, kSize, kSize);
    // `direct` as many frames as grb: the same still frames, so that the same direct light is under both.
    const int frames = directions / 16;
    for (int i = 0; i < frames; ++i) r.renderFrame(false);
    return {r.image(), r.frame().read(r.frame().indirect()), r.frame().readEmission()};
}

// Pixels that see no emitter, nor have a neighbour that does.
std::vector<bool> awayFromEmitters(const core::Image& emission)
{
    std::vector<bool> keep(std::size_t(kSize) * kSize, true);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec3 e = emission.at(x, y);
            if (std::max({e.x, e.y, e.z}) <= 0.0f) continue;
            for (int j = std::max(y - 1, 0); j <= std::min(y + 1, kSize - 1); ++j)
                for (int i = std::max(x - 1, 0); i <= std::min(x + 1, kSize - 1); ++i)
                    keep[std::size_t(j) * kSize + i] = false;
        }
    return keep;
}

core::Image masked(core::Image img, const std::vector<bool>& keep)
{
    for (std::size_t i = 0; i < keep.size(); ++i)
        if (!keep[i]) img.rgb[3 * i] = img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = 0.0f;
    return img;
}

double mean(const core::Image& img)
{
    double s = 0.0;
    for (float v : img.rgb) s += v;
    return s / double(std::max<std::size_t>(img.rgb.size(), 1));
}

class GrbReference : public GlTest, public ::testing::WithParamInterface<std::string> {};
class GrbReferenceDirect : public GlTest {};

// A parameter ending in "-bundles" runs the scene with emitters=bundles: grb's texture then also holds the
// emitters' light (diffuse from the direct atlas, glossy from the final glossy bounce, and through the
// glossy transfer's sampled emitters, whose shadow cubes the frame renders for grb alone), so it is
// compared with full - direct + the path tracer's direct light less the emission the frame still shows
// (none away from the emitter): full itself.
TEST_P(GrbReference, MatchesThePathTracersFullLightPaths)
{
    const std::string kBundles = "-bundles";
    const bool bundles = GetParam().ends_with(kBundles);
    const std::string name = bundles ? GetParam().substr(0, GetParam().size() - kBundles.size()) : GetParam();
    const core::Scene scene = core::makeCornell(name);
    const core::Image full = reference(scene, ref::LightPaths::Full);
    const core::Image direct = reference(scene, ref::LightPaths::Direct);
    const Rendered grb = render(scene, "grb", {bundles ? "emitters=bundles" : "emitters=frame"});
    const Rendered base = render(scene, "direct");
    const std::vector<bool> keep = awayFromEmitters(grb.emission);

    core::Image wantIndirect = full;
    if (!bundles)
        for (std::size_t i = 0; i < wantIndirect.rgb.size(); ++i) wantIndirect.rgb[i] -= direct.rgb[i];
    const double got = mean(masked(grb.indirect, keep)), want = mean(masked(wantIndirect, keep));
    const double errGrb = core::relativeRmse(masked(grb.image, keep), masked(full, keep));
    const double errDirect = core::relativeRmse(masked(base.image, keep), masked(full, keep));
    std::printf("[ %-12s] mean indirect %.5f (path tracer %.5f, %+.1f%%); relative RMSE against full: grb %.4f, "
                "direct %.4f\n",
                GetParam().c_str(), got, want, 100.0 * (got / want - 1.0), errGrb, errDirect);
    // Tolerances: the bundles' energy within 10%. Measured at these settings: cornell-area -3.6%,
    // cornell-spot -5.6%, cornell-glossy -1.6%. A bounce missing or counted twice moves it by 30% to 100%.
    // Taken in the plain Halton order, whose consecutive directions are correlated (bundle_directions.h),
    // cornell-area read +14.7%; with the emitters' glossy reflection carried by the bundles instead of
    // sampled (transfer.frag, AREA_GLOSSY), cornell-glossy read -13.7%. The image's error at most 50% of
    // `direct`'s (cornell-glossy 60%), whose only fault is the missing indirect light: both over the same
    // 12 still frames, so with the same direct light (grb's error over direct's, measured: area 0.157 /
    // 0.704, spot 0.137 / 0.900, glossy 0.341 / 0.840, glossy-bundles 0.651; in the plain Halton order
    // area 0.315, with the glossy transfer's emitters through the bundles glossy 0.574, both before the
    // still frames' weighted mean of the indirect light).
    EXPECT_NEAR(got, want, 0.1 * want);
    // cornell-glossy-bundles: +0.4%, but its error 0.651 / 0.840: 192 directions of a 13 x 10 cm light's
    // direct light per pixel (GrbReferenceDirect); its mean is what this case is for.
    EXPECT_LT(errGrb, (bundles ? 0.95 : name == "cornell-glossy" ? 0.6 : 0.5) * errDirect);
}

INSTANTIATE_TEST_SUITE_P(Cornell, GrbReference,
                         ::testing::Values("cornell-area", "cornell-spot", "cornell-glossy", "cornell-glossy-bundles"),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                             std::string n = p.param;

                             for (char& c : n)
                                 if (c == '-') c = '_';
                             return n;
                         });

// Sec. 5.1: the bundles carry the light of emitting surfaces, and with emitters=bundles the technique
// shows it in place of the frame's (which then leaves emitters out). One bounce (interleaved=0) on
// cornell-area, whose only light is its emitter, is then emission plus the bundles' direct light: the
// path tracer's `direct`. 768 directions; pixels next to an emitter pixel left out.
TEST_F(GrbReferenceDirect, BundlesCarryTheEmittersDirectLight)
{
    const core::Scene scene = core::makeCornell("cornell-area");
    const core::Image direct = reference(scene, ref::LightPaths::Direct);
    const Rendered grb = render(scene, "grb", {"emitters=bundles", "interleaved=0"}, 768);
    const std::vector<bool> keep = awayFromEmitters(grb.emission);
    const double got = mean(masked(grb.image, keep)), want = mean(masked(direct, keep));
    const double err = core::relativeRmse(masked(grb.image, keep), masked(direct, keep));
    std::printf("[ bundles  ] mean %.5f (path tracer's direct %.5f, %+.1f%%), relative RMSE %.4f\n", got, want,
                100.0 * (got / want - 1.0), err);
    // Measured: mean +1.5%, relative RMSE 0.374 (per pixel: the sum of 768 parallel projections of a
    // 13 x 10 cm light, streaks a texel wide at these settings). Without the direct atlas on screen the
    // image is emission only (-100%, relative RMSE 1); with the frame's emitters as well it is doubled.
    // With the still frames' latest indirect light instead of its weighted mean over the frames' sample
    // positions (glsl/frame/accumulate.comp), +6.4% and 0.763; weighted by n instead of n^3, 0.434.
    EXPECT_NEAR(got, want, 0.1 * want);
    EXPECT_LT(err, 0.55);
}

// cornell-glossy (the tall block a rough metal) or cornell-area (diffuse) lit by cornell-spot's spot alone,
// the ceiling's emitter dark: a punctual light, whose direct light the frame seeds the senders with, so
// that grb's one bounce (interleaved=0) is the path tracer's.
core::Scene underTheSpot(const std::string& name)
{
    core::Scene scene = core::makeCornell(name);
    for (core::Material& m : scene.materials) m.emission = glm::vec3(0.0f);
    scene.lights = core::makeCornell("cornell-spot").lights;
    return scene;
}

// Sec. 5.3-5.4's glossy paths against the path tracer's one bounce (interleaved=0) on cornell-glossy under
// a spot: over the pixels that see no emitter, and over those where the metal makes the one-bounce light at
// least 25% brighter than the same box with a diffuse block: the floor and walls the metal lights (the
// glossy transfer) and the block's faces that mirror the lit room (the final glossy bounce).
TEST_F(GrbReferenceDirect, GlossyPathsMatchThePathTracersOneBounce)
{
    const core::Scene glossy = underTheSpot("cornell-glossy");
    const core::Image want = reference(glossy, ref::LightPaths::OneBounceIndirect);
    const core::Image diffuse = reference(underTheSpot("cornell-area"), ref::LightPaths::OneBounceIndirect);
    const Rendered grb = render(glossy, "grb", {"emitters=frame", "interleaved=0"}, 384);
    const std::vector<bool> keep = awayFromEmitters(grb.emission);
    std::vector<bool> lit = keep;
    auto luminance = [](const core::Image& img, std::size_t i) {
        return 0.2126 * img.rgb[3 * i] + 0.7152 * img.rgb[3 * i + 1] + 0.0722 * img.rgb[3 * i + 2];
    };
    int litPixels = 0;
    for (std::size_t i = 0; i < lit.size(); ++i) {
        lit[i] = lit[i] && luminance(want, i) > 1.25 * luminance(diffuse, i);
        litPixels += lit[i];
    }
    const double got = mean(masked(grb.indirect, keep)), wanted = mean(masked(want, keep));
    const double gotLit = mean(masked(grb.indirect, lit)), wantLit = mean(masked(want, lit));
    const double err = core::relativeRmse(masked(grb.indirect, keep), masked(want, keep));
    const double errLit = core::relativeRmse(masked(grb.indirect, lit), masked(want, lit));
    std::printf("[ glossy   ] one bounce: mean %.5f (path tracer %.5f, %+.1f%%), relative RMSE %.4f; where the metal "
                "lights (%d pixels): mean %.5f (%.5f, %+.1f%%), relative RMSE %.4f\n",
                got, wanted, 100.0 * (got / wanted - 1.0), err, litPixels, gotLit, wantLit,
                100.0 * (gotLit / wantLit - 1.0), errLit);
    // Measured: +2.2% and +1.0% (before one-bounce senders sent their lobe's reflection of the direct light:
    // -37% and -65%; with the lobe reflecting the seeded diffuse light too, a second bounce: +15.8%). The
    // relative RMSE per pixel (1.15 and 2.3) is the spot's reflection off the block's top on the ceiling,
    // a sharp patch that 384 directions on an atlas of 8192 texels place a pixel or two off; the means are
    // the test.
    ASSERT_GT(litPixels, 30);
    EXPECT_NEAR(got, wanted, 0.06 * wanted);
    EXPECT_NEAR(gotLit, wantLit, 0.1 * wantLit);
}

// With emitters=bundles the frame's direct pass leaves emitters out, and its shadow pass skips their cubes
// unless grb samples them (the glossy transfer in a glossy scene): cornell-area draws none of them,
// cornell-glossy all, and emitters=frame all.
TEST_F(GrbReferenceDirect, FrameDrawsTheEmittersCubesOnlyWhereSomethingReadsThem)
{
    const auto areaViewsDrawn = [](const std::string& name, const std::string& emitters, int* all) {
        const core::Scene scene = core::makeCornell(name);
        const gl::TechniqueInfo& info = gl::findTechnique("grb");
        gl::ParamValues f(gl::frameParams()), t(info.params);
        f.setValue("shadow.size", 64);
        for (const std::string& kv : info.quickSets) {
            const std::size_t eq = kv.find('=');
            t.set(info.params, kv.substr(0, eq), kv.substr(eq + 1));
        }
        t.set(info.params, "emitters", emitters);
        gl::Renderer r(scene, "grb", f, t, 16, 16);
        r.renderFrame(false);
        const gl::ShadowMaps& maps = r.frame().shadowMaps();
        int drawn = 0;
        *all = 0;
        for (std::size_t i = 0; i < maps.views().size(); ++i) {
            if (maps.views()[i].areaCount == 0) continue;
            ++*all;
            drawn += maps.renders(i) ? 1 : 0;
        }
        EXPECT_EQ(r.frame().areaLightsInDirect(), emitters == "frame") << name;
        return drawn;
    };
    int all = 0;
    EXPECT_EQ(areaViewsDrawn("cornell-area", "bundles", &all), 0);
    EXPECT_EQ(all, 6);
    EXPECT_EQ(areaViewsDrawn("cornell-glossy", "bundles", &all), all);
    EXPECT_EQ(all, 6);
    EXPECT_EQ(areaViewsDrawn("cornell-area", "frame", &all), all);
}

} // namespace
} // namespace bounce
