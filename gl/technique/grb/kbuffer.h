// The k-buffer of one global ray-bundle (Hermes et al. 2010, Sec. 4.2): the whole scene rasterised once
// along the direction, no depth test, no culling, every fragment an entry (atlas texel + 1, depth) of
// its pixel (glsl/technique/grb/kbuffer.glsl reads them). Three captures of the same entries:
//   Stencil: the paper's stencil routing (Bavoil et al. 2007): a multisample target of S samples whose
//     stencils start at their own index (plus the slice's offset); the stencil test EQUAL with decrement
//     on every outcome sends the i-th fragment of a pixel to sample i. k = S x slices, one geometry pass
//     per slice. Exact only where every fragment reaches every sample's stencil test (StencilProbe).
//   Atomic: a per-pixel image-atomic counter gives each fragment its slot in a fixed array; exact.
//   Peel: depth peeling (Everitt 2001), one geometry pass per layer: the reference.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gl/frame/frame.h"
#include "gl/resource/framebuffer.h"
#include "gl/resource/program.h"
#include "gl/resource/query.h"
#include "gl/resource/texture.h"
#include "gl/resource/timer.h"
#include "gl/technique/grb/bundle_directions.h"
#include "gl/technique/grb/grb_atlas.h"

namespace bounce::gl {

enum class KBufferCapture { Stencil, Atomic, Peel };
std::string kbufferCaptureName(KBufferCapture c);

struct KBufferSettings {
    KBufferCapture capture = KBufferCapture::Atomic;
    int size = 256;           // pixels per side
    int k = 8;                // entries per pixel (Stencil: rounded up to a multiple of the samples)
    int samples = 8;          // Stencil: samples per slice (at most the driver's)
    bool multisample = false; // Stencil: GL_MULTISAMPLE during the capture (see StencilProbe)
    bool alphaMask = false;   // the scene has alpha-masked materials: their holes capture nothing
};

// The driver's largest sample count for the stencil-routed k-buffer (colour RG32F and depth-stencil).
int maxKBufferSamples();

class KBuffer {
public:
    explicit KBuffer(const KBufferSettings& settings);

    // Rasterises the scene along `view` into the k-buffer (pass "capture"). Binds the frame's scene data
    // and the atlas's corners itself.
    void capture(const Frame& frame, const GrbAtlas& atlas, const BundleView& view, PassTimers& timers);
    // The entries and their counts or overflow marks at UNIT_GRB_KBUFFER.. for kbuffer.glsl.
    void bindForRead() const;
    // KBUFFER_<capture>, KBUFFER_K, KBUFFER_SAMPLES: what kbuffer.glsl is compiled for.
    std::vector<Define> readerDefines() const;
    // The bundle's uniforms of bundle.glsl.
    static void setBundleUniforms(Program& program, const BundleView& view);
    // kbuffer.glsl's bundleSender for one receiver, counted (part of the PassCost of "transfer" and
    // "final-glossy"): the projection and the plane's depth, the count or stencil, two passes over k entries
    // (Stencil, Peel: all k; Atomic: at most k, the count only the GPU knows), with `charts` the chart of each
    // entry near the receiver's depth (at most k: a bound).
    PassCost bundleSenderCost(bool charts) const;

    // Every pixel's entries as kbuffer.glsl reads them (row-major, pixel y * size + x), sorted by depth,
    // with the count (Atomic: the fragments; Peel, Stencil: the entries, plus one when it overflowed).
    struct Pixel {
        std::vector<std::pair<float, std::uint32_t>> entries; // (depth, atlas texel)
        std::uint32_t count = 0;
        bool overflow = false;
    };
    std::vector<Pixel> readBack();
    // Whether two captures hold the same entries at a pixel: the same atlas texels in the same depth order,
    // depths equal to within a few ulps. A multisample capture interpolates depth along its own path and
    // may differ from a single-sample one in the last bit (seen on llvmpipe and NVIDIA's driver); the
    // transfer only orders the entries by depth, so such a difference changes nothing.
    static bool sameEntries(const Pixel& a, const Pixel& b);

    KBufferCapture capture() const { return settings_.capture; }
    int size() const { return settings_.size; }
    int k() const { return k_; }
    int samples() const { return samples_; }
    int slices() const { return slices_; }
    int peeledLayers() const { return peeled_; } // Peel: layers the last capture found (<= k)
    const KBufferSettings& settings() const { return settings_; }

private:
    KBufferSettings settings_;
    int k_ = 0, samples_ = 1, slices_ = 1, peeled_ = 0;
    Texture entries_, count_, stencil_, peelTexel_, peelPrevious_, peelDepth_;
    Framebuffer fbo_, initFbo_, peelFbo_, overflowFbo_;
    VertexArray vao_;
    Program captureProgram_, initProgram_, overflowProgram_, composeProgram_, readProgram_;
    Query anySamples_;
    void captureStencil(const GrbAtlas& atlas, const BundleView& view);
    void captureAtomic(const GrbAtlas& atlas, const BundleView& view);
    void capturePeel(const GrbAtlas& atlas, const BundleView& view);
    void drawScene(Program& program, const GrbAtlas& atlas, const BundleView& view);
};

// Depth complexity along `directions` bundle directions (the first ones of the sequence): fragments per
// pixel counted with an image-atomic counter, the largest over all pixels and directions.
struct DepthComplexity {
    int largest = 0;
    double meanOccupied = 0.0; // mean fragments per pixel that holds any
    int directions = 0;
};
DepthComplexity measureDepthComplexity(const Frame& frame, const GrbAtlas& atlas, int size, int directions,
                                       PassTimers& timers);

// Whether stencil routing with `samples` samples per slice (clamped to maxKBufferSamples) is exact on the
// driver in use: a tiny scene captured by Stencil (with GL_MULTISAMPLE off, as the GL specification
// routes every fragment to every sample, then on) and by Atomic along a few directions; exact when every
// pixel holds the same entries. Run once per process for each driver and sample count: a driver may
// route exactly at one count and not at another, so the probe tests the count the capture will use.
struct StencilProbe {
    bool exact = false;
    bool multisample = false; // the GL_MULTISAMPLE setting that was exact (or the better one)
    int samples = 0;
    int mismatchedPixels = 0; // of the better setting
    int pixels = 0;
    std::string reason;
};
const StencilProbe& stencilProbe(int samples);

} // namespace bounce::gl
