// The same frame from two context backends: OSMesa (what the tests use) and EGL (what `bounce render`
// uses, and what is left once Mesa drops OSMesa) must give the same image. Both are Mesa's llvmpipe
// here, so the pixels must agree to float rounding: a difference means a backend-specific path
// (entry points loaded through the wrong loader, a default state one backend sets and the other does
// not, a framebuffer read with a different layout), not a rendering choice.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "core/image.h"
#include "core/metrics.h"
#include "gl/context/context.h"
#include "gl/debug.h"
#include "gl/renderer.h"

namespace bounce {
namespace {

// Not a power of two and not square: a row-pitch or aspect mistake in one backend's read-back shows.
constexpr int kWidth = 64, kHeight = 48;

// Per value: |osmesa - egl| <= kAbsTol + kRelTol |osmesa|. The same llvmpipe compiles the same shaders
// in both, so the images are expected bit for bit equal (measured: max |diff| = 0 for direct and rsm);
// the tolerance only allows for float rounding should the two ever schedule work differently.
constexpr double kRelTol = 1e-4, kAbsTol = 1e-6;

using Sets = std::vector<std::pair<std::string, std::string>>;

struct Rendered {
    core::Image image;
    std::string renderer; // GL_RENDERER
    std::string platform; // "osmesa", "egl-surfaceless"...
};

// Creates a context of `backend`, renders one frame of `technique` on cornell-spot and reads the
// result; the renderer's GL objects are destroyed while their context is still current. GL errors
// and high-severity debug messages fail the test, as GlTest does for its own context.
Rendered renderWith(gl::Backend backend, const std::string& technique, const Sets& sets)
{
    gl::ContextOptions options;
    options.visible = false;
    options.debug = true;
    gl::resetDebugErrors();
    const auto context = gl::Context::create(backend, options);
    Rendered out;
    out.renderer = context->info().renderer;
    out.platform = context->info().platform;
    {
        const core::Scene scene = core::makeCornell("cornell-spot");
        const gl::TechniqueInfo& info = gl::findTechnique(technique);
        gl::ParamValues frameValues(gl::frameParams()), values(info.params);
        frameValues.setValue("shadow.size", 256); // llvmpipe on two cores: keep the frame small
        for (const auto& [k, v] : sets) values.set(info.params, k, v);
        gl::Renderer r(scene, technique, frameValues, values, kWidth, kHeight);
        r.renderFrame();
        out.image = r.image();
    }
    gl::checkGlError(gl::backendName(backend));
    std::string messages;
    for (const gl::DebugMessage& m : gl::takeDebugErrors()) messages += "\n  " + m.text;
    EXPECT_TRUE(messages.empty()) << gl::backendName(backend) << ", " << technique << ":" << messages;
    return out;
}

// On a failed comparison: both images and the error heat map next to the test log.
void writeOnFailure(const std::string& name, const core::Image& osmesa, const core::Image& egl)
{
#ifdef BOUNCE_TEST_OUT
    if (!::testing::Test::HasFailure()) return;
    const std::string base = std::string(BOUNCE_TEST_OUT) + "/backend_" + name;
    std::filesystem::create_directories(BOUNCE_TEST_OUT);
    core::writeExr(base + "-osmesa.exr", osmesa);
    core::writeExr(base + "-egl.exr", egl);
    core::writePng(base + "-error.png", core::errorHeatmap(egl, osmesa));
    std::printf("wrote %s-{osmesa,egl}.exr and %s-error.png\n", base.c_str(), base.c_str());
#else
    (void)name, (void)osmesa, (void)egl;
#endif
}

// Plain TESTs, not GlTest: each makes its own two contexts (one after the other, each destroyed before
// the next is made), and GlTest suites destroy theirs at the end of the suite, so nothing else is bound.
void expectSameImage(const std::string& technique, const Sets& sets)
{
    const Rendered osmesa = renderWith(gl::Backend::OsMesa, technique, sets);
    Rendered egl;
    try {
        egl = renderWith(gl::Backend::Egl, technique, sets);
    } catch (const gl::ContextError& e) {
        GTEST_SKIP() << "no EGL context on this machine: " << e.what();
    }
    // The tolerance is for one rasteriser behind two front doors; a GPU behind EGL renders differently.
    if (egl.renderer != osmesa.renderer)
        GTEST_SKIP() << "EGL renders on '" << egl.renderer << "', OSMesa on '" << osmesa.renderer
                     << "': not the same rasteriser";
    ASSERT_EQ(egl.image.width, kWidth);
    ASSERT_EQ(egl.image.height, kHeight);
    ASSERT_EQ(osmesa.image.rgb.size(), egl.image.rgb.size());

    double maxDiff = 0.0, sum = 0.0;
    int bad = 0, firstBad = -1;
    for (std::size_t i = 0; i < osmesa.image.rgb.size(); ++i) {
        const double a = osmesa.image.rgb[i], b = egl.image.rgb[i];
        ASSERT_TRUE(std::isfinite(a) && std::isfinite(b)) << "value " << i;
        const double d = std::abs(a - b);
        maxDiff = std::max(maxDiff, d);
        sum += a;
        if (d > kAbsTol + kRelTol * std::abs(a)) {
            if (firstBad < 0) firstBad = int(i);
            ++bad;
        }
    }
    std::printf("[ backend  ] %s, %s vs %s on %s: max |diff| = %.3g (mean value %.3g)\n", technique.c_str(),
                osmesa.platform.c_str(), egl.platform.c_str(), egl.renderer.c_str(), maxDiff,
                sum / double(osmesa.image.rgb.size()));
    // A black frame from both would agree trivially.
    EXPECT_GT(sum, 0.0) << technique << " rendered black";
    EXPECT_EQ(bad, 0) << technique << ": " << bad << " values differ by more than " << kAbsTol << " + " << kRelTol
                      << " x value; the first at pixel (" << firstBad / 3 % kWidth << ", " << firstBad / 3 / kWidth
                      << ") channel " << firstBad % 3 << "; max |diff| " << maxDiff;
    writeOnFailure(technique, osmesa.image, egl.image);
}

TEST(BackendTest, DirectSameOnOsMesaAndEgl)
{
    expectSameImage("direct", {});
}

// The RSM pass, VPL sampling (compute) and the gather: storage buffers and image reads, not just
// rasterisation, go through each backend.
TEST(BackendTest, RsmSameOnOsMesaAndEgl)
{
    expectSameImage("rsm", {{"vpls", "64"}});
}

} // namespace
} // namespace bounce
