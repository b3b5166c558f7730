// The three k-buffer captures of global ray-bundles (gl/technique/grb/kbuffer.h) against each other:
// where a pixel's depth complexity is at most k, the atomic capture and depth peeling hold the same
// (depth, atlas texel) entries and the counter equals the number of peeled layers; stencil routing holds
// them too where the start-up probe finds it exact (on llvmpipe it does not: the test says how much it
// loses). A closed box gives an even number of fragments in every pixel of every direction; pixels
// beyond k are counted as overflowed (cornell-slats with k = 2); kbuffer=auto follows the probe.
#include <cstdio>

#include <gtest/gtest.h>

#include "core/cornell.h"
#include "gl/renderer.h"
#include "tests/gl/gl_test_fixture.h"
#include "tests/gl/grb_harness.h"

namespace bounce {
namespace {

using grbtest::Harness;
using grbtest::kbufferSettings;

class GrbCapture : public GlTest {};

// Captures `scene` along a few directions with `a` and `b` (same size and k); returns the pixels whose
// entries differ among those within k, and checks counts against peeled layers when b is Peel.
int differingPixels(const core::Scene& scene, gl::KBufferSettings a, gl::KBufferSettings b, int directions,
                    int* comparable = nullptr)
{
    Harness ha(scene, a, 40.0f);
    gl::KBuffer other(b);
    int bad = 0, n = 0;
    for (int d = 0; d < directions; ++d) {
        const gl::BundleView v = ha.view(gl::bundleDirection(std::uint64_t(d)), gl::bundleJitter(std::uint64_t(d)));
        ha.kbuffer().capture(ha.frame(), ha.atlas(), v, ha.timers());
        other.capture(ha.frame(), ha.atlas(), v, ha.timers());
        const auto pa = ha.kbuffer().readBack(), pb = other.readBack();
        for (std::size_t p = 0; p < pa.size(); ++p) {
            if (pa[p].overflow || pb[p].overflow) {
                EXPECT_EQ(pa[p].overflow, pb[p].overflow) << "pixel " << p << " overflowed in one capture only";
                continue;
            }
            ++n;
            if (!gl::KBuffer::sameEntries(pa[p], pb[p])) ++bad;
            if (a.capture == gl::KBufferCapture::Atomic && b.capture == gl::KBufferCapture::Peel) {
                EXPECT_EQ(pa[p].count, pb[p].entries.size()) << "pixel " << p << ": counter and peeled layers";
            }
        }
        ha.timers().endFrame(false);
    }
    if (comparable) *comparable = n;
    return bad;
}

TEST_F(GrbCapture, AtomicEqualsDepthPeeling)
{
    for (const char* name : {"cornell-area", "cornell-slats"}) {
        SCOPED_TRACE(name);
        int n = 0;
        const int bad = differingPixels(core::makeCornell(name), kbufferSettings(gl::KBufferCapture::Atomic, 48, 12),
                                        kbufferSettings(gl::KBufferCapture::Peel, 48, 12), 3, &n);
        EXPECT_EQ(bad, 0) << "of " << n << " pixels";
        EXPECT_GT(n, 3000);
    }
}

TEST_F(GrbCapture, StencilRoutingWhereExact)
{
    const gl::StencilProbe& probe = gl::stencilProbe(8);
    std::printf("[ probe    ] %s\n", probe.reason.c_str());
    gl::KBufferSettings st = kbufferSettings(gl::KBufferCapture::Stencil, 48, 8);
    st.multisample = probe.multisample;
    int n = 0;
    const int bad = differingPixels(core::makeCornell("cornell-area"), st,
                                    kbufferSettings(gl::KBufferCapture::Atomic, 48, 8), 4, &n);
    std::printf("[ stencil  ] cornell-area, 4 directions, %d samples: %d of %d pixels differ from atomic (%.2f%%)\n",
                probe.samples, bad, n, 100.0 * bad / std::max(n, 1));
    if (probe.exact)
        EXPECT_EQ(bad, 0);
    else
        EXPECT_GT(probe.mismatchedPixels, 0); // the probe's verdict agrees with what it measured
}

TEST_F(GrbCapture, WatertightBoxHasEvenCounts)
{
    core::Scene s;
    s.materials.push_back(grbtest::lambertian(0.5f));
    s.meshes.push_back(grbtest::box({0.1f, 0.2f, 0.3f}, {0.9f, 0.7f, 0.6f}, false, 0));
    s.meshes.push_back(grbtest::box({0.3f, 0.3f, 0.35f}, {0.5f, 0.6f, 0.55f}, true, 0));
    for (gl::KBufferCapture c : {gl::KBufferCapture::Atomic, gl::KBufferCapture::Peel}) {
        SCOPED_TRACE(gl::kbufferCaptureName(c));
        Harness h(s, kbufferSettings(c, 40, 8), 20.0f);
        int odd = 0, occupied = 0;
        for (int d = 0; d < 6; ++d) {
            // Axis-aligned directions too: faces edge-on, rays along the box's edges.
            const glm::vec3 dir = d < 2 ? glm::vec3(d == 0 ? 1.0f : 0.0f, d == 1 ? 1.0f : 0.0f, 0.0f)
                                        : gl::bundleDirection(std::uint64_t(d));
            h.kbuffer().capture(h.frame(), h.atlas(), h.view(dir, gl::bundleJitter(std::uint64_t(d))), h.timers());
            for (const auto& p : h.kbuffer().readBack()) {
                odd += p.count % 2;
                occupied += p.count > 0;
            }
            h.timers().endFrame(false);
        }
        EXPECT_EQ(odd, 0) << "pixels with an odd number of fragments, of " << occupied;
        EXPECT_GT(occupied, 1000);
    }
}

TEST_F(GrbCapture, OverflowIsCountedBeyondK)
{
    // cornell-slats with k = 2: rays through the slats and the shelf cross more than two surfaces.
    Harness h(core::makeCornell("cornell-slats"), kbufferSettings(gl::KBufferCapture::Atomic, 48, 2), 30.0f);
    int overflowed = 0, beyond = 0;
    for (int d = 0; d < 3; ++d) {
        h.kbuffer().capture(h.frame(), h.atlas(), h.view(gl::bundleDirection(std::uint64_t(d))), h.timers());
        for (const auto& p : h.kbuffer().readBack()) {
            overflowed += p.overflow;
            beyond += p.count > 2;
            EXPECT_LE(p.entries.size(), 2u);
        }
        h.timers().endFrame(false);
    }
    EXPECT_GT(beyond, 100);
    EXPECT_EQ(overflowed, beyond);
}

TEST_F(GrbCapture, TechniqueRecordsTheCaptureAndOverflow)
{
    const core::Scene scene = core::makeCornell("cornell-slats");
    const gl::TechniqueInfo& info = gl::findTechnique("grb");
    gl::ParamValues f(gl::frameParams()), t(info.params);
    f.setValue("shadow.size", 256);
    t.set(info.params, "kbufferSize", "32");
    t.set(info.params, "atlasTexels", "4096");
    t.set(info.params, "directionsPerFrame", "2");
    t.set(info.params, "k", "2");
    // Stencil routing rounds k up to whole slices: two samples keep k at 2 for either capture (at the
    // default 8 the slats would fit, and nothing would overflow).
    t.set(info.params, "samples", "2");
    gl::Renderer r(scene, "grb", f, t, 16, 16);
    r.renderFrame(true);
    double stencil = -1, atomic = -1, overflow = -1, exact = -1;
    for (const gl::Counter& c : r.counters()) {
        if (c.name == "capture.stencil") stencil = c.value;
        if (c.name == "capture.atomic") atomic = c.value;
        if (c.name == "overflowPixels") overflow = c.value;
        if (c.name == "stencilProbeExact") exact = c.value;
    }
    EXPECT_EQ(stencil + atomic, 1.0);
    EXPECT_EQ(stencil, exact) << "kbuffer=auto takes stencil exactly where the probe finds it exact";
    EXPECT_GT(overflow, 0.0);
    EXPECT_FALSE(r.notes().value("captureReason", "").empty());
}

} // namespace
} // namespace bounce
