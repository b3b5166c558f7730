// The same frame from two context backends: OSMesa (what the tests use) and EGL (what `bounce render`
// uses, and what is left once Mesa drops OSMesa) must give the same image. Both are Mesa's llvmpipe
// here, so the pixels must agree to float rounding: a difference means a backend-specific path
// (entry points loaded through the wrong loader, a default state one backend sets and the other does
// not, a framebuffer read with a different layout), not a rendering choice.
#include <algorithm>
#include <cmath>
#include <cstdio>
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
#include "tests/image_expect.h"

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

// Plain TESTs, not GlTest: each makes its own two contexts (one after the other, each destroyed before
// the next is made), and GlTest suites destroy theirs at the end of the suite, so nothing else is bound.
void expectSameImage(const std::string& technique, const Sets& sets)
{
    if (const std::string why = gl::osMesaUnavailable(); !why.empty()) GTEST_SKIP() << why;
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

    double sum = 0.0;
    for (float v : osmesa.image.rgb) sum += v;
    const double maxDiff = testing::measureImages(egl.image, osmesa.image, testing::ImageMetric::maxAbs());
    std::printf("[ backend  ] %s, %s vs %s on %s: max |diff| = %.3g (mean value %.3g)\n", technique.c_str(),
                osmesa.platform.c_str(), egl.platform.c_str(), egl.renderer.c_str(), maxDiff,
                sum / double(osmesa.image.rgb.size()));
    // A black frame from both would agree trivially.
    EXPECT_GT(sum, 0.0) << technique << " rendered black";
    testing::expectImagesClose(technique, egl.image, osmesa.image,
                               testing::ImageMetric::valuesOutside(kAbsTol, kRelTol), 0.0,
                               "one rasteriser behind two front doors");
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
