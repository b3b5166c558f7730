#include "gl/technique/grb/kbuffer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>

#include "core/cornell.h"
#include "gl/frame/bindings.h"
#include "gl/gl.h"
#include "gl/resource/dispatch.h"
#include "gl/resource/pass_state.h"
#include "gl/technique/grb/bindings.h"

namespace bounce::gl {

namespace {

// Stencil routing: sample i of slice j starts at kRoutingRef + i + j S; a fragment passes where the
// stencil equals kRoutingRef. 2 (not 1) so that the last sample of the last slice, which starts at 1 + k,
// is still above 0 after k fragments and at 0 after more: the overflow mark (kbuffer.glsl).
constexpr int kRoutingRef = 2;

// alphaMask: the fragments in the holes of alpha masks are discarded (capture.frag, ALPHA_MASK), so that a
// bundle's rays pass through them as the path tracer's do.
std::vector<Define> captureDefines(const char* mode, int k, bool alphaMask)
{
    std::vector<Define> d = {{mode, "1"}, {"KBUFFER_K", std::to_string(std::max(k, 1))}};
    if (alphaMask) d.push_back({"ALPHA_MASK", "1"});
    return d;
}

void clearUint(Texture& t)
{
    const GLuint zero[4] = {0, 0, 0, 0};
    glClearTexImage(t.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, zero);
}

std::vector<std::uint32_t> readUint(const Texture& t)
{
    std::vector<std::uint32_t> out(std::size_t(t.width()) * std::size_t(t.height()));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(t.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(out.size() * 4), out.data());
    return out;
}

// capture.vert per corner: its index, position and atlas corner (4 + 12 + 8 bytes); `draws` draws of the
// scene along a bundle.
PassCost sceneAlongBundle(const GrbAtlas& atlas, double draws)
{
    const double triangles = double(atlas.layout().triangleCount());
    PassCost c;
    c.triangles = draws * triangles;
    c.bytesFixed = draws * 3.0 * triangles * (4 + 12 + 8);
    return c;
}

// What a capture does, known before it runs (Peel's: peelWork). Fragments of the scene along the bundle are
// counted at k per pixel where they are not the driver's invocations: only the GPU knows how many there are,
// and k bounds them where no pixel overflows.
PassCost captureCost(const KBuffer& kb, const GrbAtlas& atlas)
{
    const double pixels = double(kb.size()) * kb.size(), k = kb.k(), samples = kb.samples(), slices = kb.slices();
    PassCost c;
    switch (kb.capture()) {
    case KBufferCapture::Atomic:
        // capture.frag (CAPTURE_ATOMIC) per fragment: its entry (atlas texel, depth), the pixel's counter
        // incremented (an image atomic), the 8-byte entry stored in its slot (none beyond k); the counter's clear.
        c = sceneAlongBundle(atlas, 1);
        c.flops = 8;
        c.fetches = 1;
        c.bytesRead = 4;
        c.bytesWritten = 4 + 8;
        c.bytesFixed += pixels * 4;
        break;
    case KBufferCapture::Stencil:
        // Two shaders with nothing in common, all per scope. Per slice: the colour clear (8 bytes per entry),
        // stencil_init.frag per pixel and sample one stencil (4 bytes, D24S8), capture.frag per fragment its
        // entry and all S stencils read and decremented (k per pixel), each of the slice's entries written once.
        c = sceneAlongBundle(atlas, slices);
        c.flopsFixed = slices * k * pixels * 6;
        c.bytesFixed += slices * (pixels * samples * (8 + 4 + 8) + k * pixels * samples * (4 + 4));
        break;
    case KBufferCapture::Peel: break;
    }
    return c;
}

// Depth peeling, once it ran (L layers peeled): 2 L + 1 draws of the scene (the last finds nothing or marks
// the overflow); capture.frag per fragment (k per pixel) at most: the previous layer's texel (8 bytes), the
// depth test (4) and a depth write or the texel's MIN blend (8 read, 8 written); peel_compose.frag per pixel
// and layer: one texel in, two entries out; the clears of the k-buffer, its copy, the overflow marks, and per
// layer tried the peel's texel and depth.
PassCost peelWork(const KBuffer& kb, const GrbAtlas& atlas)
{
    const double pixels = double(kb.size()) * kb.size(), k = kb.k(), layers = kb.peeledLayers();
    const double draws = 2 * layers + 1, tried = layers + (layers < k ? 1 : 0), fragments = draws * k * pixels;
    PassCost c = sceneAlongBundle(atlas, draws);
    c.flopsFixed = fragments * 12 + layers * pixels * 2;
    c.fetchesFixed = fragments + layers * pixels;
    c.bytesFixed += fragments * (8 + 4 + 8 + 8) + layers * pixels * (8 + 2 * 8) + pixels * (k * 8 + 8 + 4) +
                    tried * pixels * (8 + 4);
    return c;
}

} // namespace

std::string kbufferCaptureName(KBufferCapture c)
{
    switch (c) {
    case KBufferCapture::Stencil: return "stencil";
    case KBufferCapture::Atomic: return "atomic";
    default: return "peel";
    }
}

int maxKBufferSamples()
{
    GLint colour = 1, depth = 1, general = 1;
    glGetIntegerv(GL_MAX_COLOR_TEXTURE_SAMPLES, &colour);
    glGetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &depth);
    glGetIntegerv(GL_MAX_SAMPLES, &general);
    return std::max(1, std::min({colour, depth, general}));
}

KBuffer::KBuffer(const KBufferSettings& settings)
    : settings_(settings),
      fbo_("grb.kbuffer.fbo"),
      initFbo_("grb.kbuffer.init"),
      vao_("grb.kbuffer.scene"),
      anySamples_(GL_ANY_SAMPLES_PASSED, "grb.kbuffer.peel")
{
    if (settings.size < 1 || settings.k < 1) throw std::invalid_argument("k-buffer: size and k must be positive");
    const int n = settings.size;
    switch (settings.capture) {
    case KBufferCapture::Stencil: {
        samples_ = std::min(settings.samples, maxKBufferSamples());
        slices_ = (settings.k + samples_ - 1) / samples_;
        k_ = samples_ * slices_;
        if (1 + k_ > 255) throw std::invalid_argument("k-buffer: stencil routing holds at most 254 entries");
        entries_ = Texture::create2DMultisampleArray("grb.kbuffer.entries", GL_RG32F, n, n, samples_, slices_);
        stencil_ = Texture::create2DMultisample("grb.kbuffer.stencil", GL_DEPTH24_STENCIL8, n, n, samples_);
        glTextureParameteri(stencil_.id(), GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
        fbo_.attach(GL_DEPTH_STENCIL_ATTACHMENT, stencil_);
        captureProgram_ =
            Program::graphics("grb.capture.stencil", "technique/grb/capture.vert", "technique/grb/capture.frag",
                              captureDefines("CAPTURE_STENCIL", k_, settings.alphaMask));
        initProgram_ =
            Program::graphics("grb.stencil.init", "frame/fullscreen.vert", "technique/grb/stencil_init.frag");
        break;
    }
    case KBufferCapture::Atomic:
        k_ = settings.k;
        entries_ = Texture::create2DArray("grb.kbuffer.entries", GL_RG32F, n, n, k_);
        count_ = Texture::create2D("grb.kbuffer.count", GL_R32UI, n, n);
        fbo_.setDefaultSize(n, n);
        captureProgram_ =
            Program::graphics("grb.capture.atomic", "technique/grb/capture.vert", "technique/grb/capture.frag",
                              captureDefines("CAPTURE_ATOMIC", k_, settings.alphaMask));
        break;
    case KBufferCapture::Peel:
        k_ = settings.k;
        entries_ = Texture::create2DArray("grb.kbuffer.entries", GL_RG32F, n, n, k_);
        count_ = Texture::create2D("grb.kbuffer.overflow", GL_R32UI, n, n);
        peelTexel_ = Texture::create2D("grb.kbuffer.peelTexel", GL_RG32F, n, n);
        peelPrevious_ = Texture::create2D("grb.kbuffer.peelPrevious", GL_RG32F, n, n);
        peelDepth_ = Texture::create2D("grb.kbuffer.peelDepth", GL_DEPTH_COMPONENT32F, n, n);
        peelFbo_ = Framebuffer("grb.kbuffer.peel");
        peelFbo_.attach(GL_COLOR_ATTACHMENT0, peelTexel_);
        peelFbo_.attach(GL_DEPTH_ATTACHMENT, peelDepth_);
        peelFbo_.checkComplete();
        overflowFbo_ = Framebuffer("grb.kbuffer.overflow");
        overflowFbo_.attach(GL_COLOR_ATTACHMENT0, count_);
        overflowFbo_.checkComplete();
        composeProgram_ =
            Program::graphics("grb.peel.compose", "frame/fullscreen.vert", "technique/grb/peel_compose.frag");
        captureProgram_ =
            Program::graphics("grb.capture.peel", "technique/grb/capture.vert", "technique/grb/capture.frag",
                              captureDefines("CAPTURE_PEEL", k_, settings.alphaMask));
        overflowProgram_ =
            Program::graphics("grb.capture.overflow", "technique/grb/capture.vert", "technique/grb/capture.frag",
                              captureDefines("CAPTURE_OVERFLOW", k_, settings.alphaMask));
        break;
    }
}

std::vector<Define> KBuffer::readerDefines() const
{
    std::vector<Define> d;
    switch (settings_.capture) {
    case KBufferCapture::Stencil: d.push_back({"KBUFFER_STENCIL", "1"}); break;
    case KBufferCapture::Atomic: d.push_back({"KBUFFER_ATOMIC", "1"}); break;
    case KBufferCapture::Peel: d.push_back({"KBUFFER_PEEL", "1"}); break;
    }
    d.push_back({"KBUFFER_K", std::to_string(k_)});
    d.push_back({"KBUFFER_SAMPLES", std::to_string(samples_)});
    return d;
}

void KBuffer::setBundleUniforms(Program& p, const BundleView& v)
{
    p.set("bundleDir", v.dir);
    p.set("bundleRight", v.right);
    p.set("bundleUp", v.up);
    p.set("bundleCentre", v.centre);
    p.set("bundleRadius", v.radius);
    p.set("kbufferSize", v.size);
    p.set("bundleJitter", v.jitter);
    p.set("bundleViewProj", v.viewProj);
}

PassCost KBuffer::bundleSenderCost(bool charts) const
{
    // About 100 flops before the entries (two projections, the plane's depth, the tolerances); per entry
    // two 8-byte reads and about 14 flops, and with charts an RGBA32F texel of the atlas and 4.
    const double k = k_;
    PassCost c;
    c.flops = 100 + k * (14 + (charts ? 4 : 0));
    c.fetches = 1 + k * (2 + (charts ? 1 : 0));
    c.bytesRead = 4 + k * (2 * 8 + (charts ? 16 : 0));
    return c;
}

void KBuffer::bindForRead() const
{
    entries_.bind(UNIT_GRB_KBUFFER);
    if (settings_.capture == KBufferCapture::Stencil)
        stencil_.bind(UNIT_GRB_KBUFFER_STENCIL);
    else
        count_.bind(UNIT_GRB_KBUFFER_COUNT);
}

void KBuffer::drawScene(Program& program, const GrbAtlas& atlas, const BundleView& view)
{
    setBundleUniforms(program, view);
    program.set("atlasWidth", atlas.width());
    program.set("depthScale", 0.5f / view.radius);
    program.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(3 * atlas.layout().triangleCount()));
}

void KBuffer::capture(const Frame& frame, const GrbAtlas& atlas, const BundleView& view, PassTimers& timers)
{
    auto t = timers.scope("capture", captureCost(*this, atlas));
    frame.bindSceneData();
    atlas.bind();
    switch (settings_.capture) {
    case KBufferCapture::Stencil: captureStencil(atlas, view); break;
    case KBufferCapture::Atomic: captureAtomic(atlas, view); break;
    case KBufferCapture::Peel:
        capturePeel(atlas, view);
        t.addWork(peelWork(*this, atlas));
        break;
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void KBuffer::captureStencil(const GrbAtlas& atlas, const BundleView& view)
{
    const int n = settings_.size;
    for (int slice = 0; slice < slices_; ++slice) {
        fbo_.attachLayer(GL_COLOR_ATTACHMENT0, entries_, slice);
        const float zero[4] = {0, 0, 0, 0};
        PassState clear = PassState::fullscreen(fbo_, n, n);
        clear.apply();
        glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, zero);
        // Each sample's stencil to its index plus the slice's offset, through the sample mask.
        PassState init = PassState::fullscreen(fbo_, n, n);
        init.multisample = true;
        init.colorMask = glm::bvec4(false);
        init.stencil.test = true;
        init.stencil.func = GL_ALWAYS;
        init.stencil.depthPass = GL_REPLACE;
        // The fixed-function sample mask as well as gl_SampleMask: drivers honour one or the other.
        glEnable(GL_SAMPLE_MASK);
        for (int i = 0; i < samples_; ++i) {
            init.stencil.ref = kRoutingRef + i + slice * samples_;
            init.apply();
            glSampleMaski(0, 1u << i);
            initProgram_.set("sampleIndex", i);
            initProgram_.use();
            vao_.bind();
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
        glSampleMaski(0, ~0u);
        glDisable(GL_SAMPLE_MASK);
        // Routing: the sample whose stencil equals the reference takes the fragment; every sample is
        // decremented on every fragment, so the next one goes to the next sample.
        PassState route = PassState::fullscreen(fbo_, n, n);
        route.multisample = settings_.multisample;
        route.stencil.test = true;
        route.stencil.func = GL_EQUAL;
        route.stencil.ref = kRoutingRef;
        route.stencil.stencilFail = route.stencil.depthFail = route.stencil.depthPass = GL_DECR;
        route.apply();
        drawScene(captureProgram_, atlas, view);
    }
}

void KBuffer::captureAtomic(const GrbAtlas& atlas, const BundleView& view)
{
    const int n = settings_.size;
    clearUint(count_);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    PassState::fullscreen(fbo_, n, n).apply();
    count_.bindImage(0, GL_READ_WRITE, 0, GL_R32UI);
    entries_.bindImage(1, GL_WRITE_ONLY, 0, GL_RG32F);
    drawScene(captureProgram_, atlas, view);
}

void KBuffer::capturePeel(const GrbAtlas& atlas, const BundleView& view)
{
    const int n = settings_.size;
    if (double(atlas.width()) * double(atlas.height()) >= double(1 << 24))
        throw std::invalid_argument("k-buffer: depth peeling orders texels as floats, exact for atlases below 2^24 "
                                    "texels; this one has " +
                                    std::to_string(atlas.width()) + "x" + std::to_string(atlas.height()));
    const float zero[4] = {0, 0, 0, 0}, none[4] = {3e38f, 3e38f, 0, 0};
    entries_.clear(0, zero);
    peelPrevious_.clear(0, zero);
    clearUint(count_);
    peeled_ = 0;
    bool more = true;
    for (int layer = 0; layer < k_ && more; ++layer) {
        captureProgram_.set("firstLayer", layer == 0 ? 1 : 0);
        peelPrevious_.bind(UNIT_GRB_KBUFFER);
        // The nearest depth beyond the previous layer...
        PassState s = PassState::fullscreen(peelFbo_, n, n);
        s.apply(); // clears obey the write masks: clear before masking colour
        glClearNamedFramebufferfv(peelFbo_.id(), GL_COLOR, 0, none);
        glClearNamedFramebufferfi(peelFbo_.id(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
        s.depthTest = true;
        s.colorMask = glm::bvec4(false);
        s.apply();
        {
            auto q = anySamples_.scope();
            drawScene(captureProgram_, atlas, view);
        }
        more = anySamples_.result() != 0;
        if (!more) break;
        // ...and the smallest texel at exactly that depth.
        s.colorMask = glm::bvec4(true);
        s.depthFunc = GL_EQUAL;
        s.depthWrite = false;
        s.blend = true;
        s.blendEquation = GL_MIN;
        s.apply();
        drawScene(captureProgram_, atlas, view);
        // Into the k-buffer's layer and the copy the next layer reads.
        fbo_.attachLayer(GL_COLOR_ATTACHMENT0, entries_, layer);
        fbo_.attach(GL_COLOR_ATTACHMENT1, peelPrevious_);
        fbo_.setDrawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1});
        PassState::fullscreen(fbo_, n, n).apply();
        peelTexel_.bind(UNIT_GRB_KBUFFER);
        composeProgram_.use();
        vao_.bind();
        glDrawArrays(GL_TRIANGLES, 0, 3);
        ++peeled_;
    }
    if (!more) return;
    // One more layer beyond the last marks the pixels that overflowed.
    PassState s = PassState::fullscreen(overflowFbo_, n, n);
    s.apply();
    peelPrevious_.bind(UNIT_GRB_KBUFFER);
    overflowProgram_.set("firstLayer", 0);
    drawScene(overflowProgram_, atlas, view);
}

std::vector<KBuffer::Pixel> KBuffer::readBack()
{
    const int n = settings_.size;
    if (!readProgram_)
        readProgram_ = Program::compute("grb.kbuffer.read", "technique/grb/kbuffer_read.comp", readerDefines());
    Texture entries = Texture::create2DArray("grb.kbuffer.readEntries", GL_RG32F, n, n, k_);
    Texture counts = Texture::create2D("grb.kbuffer.readCounts", GL_R32UI, n, n);
    bindForRead();
    entries.bindImage(0, GL_WRITE_ONLY, 0, GL_RG32F);
    counts.bindImage(1, GL_WRITE_ONLY, 0, GL_R32UI);
    readProgram_.set("kbufferSize", n);
    dispatchCompute(readProgram_, {n, n, 1}, {8, 8, 1});
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    const std::vector<float> e = entries.readFloats(0, 2);
    const std::vector<std::uint32_t> c = readUint(counts);
    std::vector<Pixel> out(std::size_t(n) * std::size_t(n));
    for (std::size_t p = 0; p < out.size(); ++p) {
        out[p].count = c[p] & 0x7FFFFFFFu;
        out[p].overflow = (c[p] & 0x80000000u) != 0;
        for (int i = 0; i < k_; ++i) {
            const float* v = &e[(std::size_t(i) * out.size() + p) * 2];
            std::uint32_t texel = 0;
            std::memcpy(&texel, &v[0], 4);
            if (texel != 0) out[p].entries.push_back({v[1], texel - 1});
        }
        std::sort(out[p].entries.begin(), out[p].entries.end());
    }
    return out;
}

bool KBuffer::sameEntries(const Pixel& a, const Pixel& b)
{
    if (a.entries.size() != b.entries.size()) return false;
    for (std::size_t i = 0; i < a.entries.size(); ++i) {
        const auto &ea = a.entries[i], &eb = b.entries[i];
        if (ea.second != eb.second) return false;
        if (std::abs(ea.first - eb.first) >
            4.0f * std::numeric_limits<float>::epsilon() * std::max(1.0f, std::abs(ea.first)))
            return false;
    }
    return true;
}

DepthComplexity measureDepthComplexity(const Frame& frame, const GrbAtlas& atlas, int size, int directions,
                                       PassTimers& timers)
{
    // capture.frag (CAPTURE_COUNT) per fragment: the pixel's counter incremented (an image atomic); per
    // direction the counter's clear and read-back, and one draw of the scene.
    PassCost cost = sceneAlongBundle(atlas, directions);
    cost.flops = 3;
    cost.fetches = 1;
    cost.bytesRead = 4;
    cost.bytesWritten = 4;
    cost.bytesFixed += double(directions) * size * size * (4 + 4);
    auto t = timers.scope("depth-complexity", cost);
    Texture counter = Texture::create2D("grb.depthComplexity.counter", GL_R32UI, size, size);
    Framebuffer fbo("grb.depthComplexity.fbo");
    fbo.setDefaultSize(size, size);
    VertexArray vao("grb.depthComplexity.scene");
    Program program = Program::graphics("grb.capture.count", "technique/grb/capture.vert", "technique/grb/capture.frag",
                                        captureDefines("CAPTURE_COUNT", 1, frame.gpuScene().hasAlphaMask()));
    frame.bindSceneData();
    atlas.bind();
    DepthComplexity dc;
    double occupied = 0.0, fragments = 0.0;
    for (int d = 0; d < directions; ++d) {
        clearUint(counter);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
        PassState::fullscreen(fbo, size, size).apply();
        counter.bindImage(0, GL_READ_WRITE, 0, GL_R32UI);
        const BundleView v = bundleView(frame.gpuScene().bounds(), bundleDirection(std::uint64_t(d)),
                                        bundleJitter(std::uint64_t(d)), size);
        KBuffer::setBundleUniforms(program, v);
        program.set("atlasWidth", atlas.width());
        program.use();
        vao.bind();
        glDrawArrays(GL_TRIANGLES, 0, GLsizei(3 * atlas.layout().triangleCount()));
        glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
        for (std::uint32_t c : readUint(counter)) {
            dc.largest = std::max(dc.largest, int(c));
            if (c > 0) occupied += 1.0, fragments += double(c);
        }
    }
    dc.directions = directions;
    dc.meanOccupied = occupied > 0.0 ? fragments / occupied : 0.0;
    return dc;
}

namespace {

// Pixels whose entries differ between two captures of the same direction, among the pixels that did
// not overflow the smaller one.
int mismatchedPixels(const std::vector<KBuffer::Pixel>& a, const std::vector<KBuffer::Pixel>& b, int k)
{
    int bad = 0;
    for (std::size_t p = 0; p < a.size(); ++p) {
        if (int(b[p].count) > k) continue; // beyond k the captures keep different subsets
        if (!KBuffer::sameEntries(a[p], b[p]) || a[p].overflow != b[p].overflow) ++bad;
    }
    return bad;
}

StencilProbe runStencilProbe(int samples)
{
    // cornell-slats at a k-buffer of 32^2: thin slats whose edges cross pixels at every angle, and
    // depth complexity within k = 8 (two slices of 4 on llvmpipe).
    const core::Scene scene = core::makeCornell("cornell-slats");
    FrameSettings fs;
    fs.width = fs.height = 4;
    fs.shadowMapSize = 16;
    Frame frame(scene, fs);
    core::AtlasSettings as;
    as.texelsPerMetre = 64.0f;
    GrbAtlas atlas(scene, as);
    PassTimers timers;
    atlas.fill(frame, timers);
    StencilProbe probe;
    probe.samples = samples;
    constexpr int kSize = 32, kDirections = 4, kEntries = 8;
    KBufferSettings ks;
    ks.size = kSize;
    // Stencil routing holds a whole number of slices: the atomic capture it is compared with gets as many
    // entries, so that both overflow at the same pixels (a driver with 32 samples holds 32, not 8).
    ks.k = (kEntries + probe.samples - 1) / probe.samples * probe.samples;
    ks.samples = probe.samples;
    ks.capture = KBufferCapture::Atomic;
    KBuffer atomic(ks);
    int best = -1;
    for (bool multisample : {false, true}) {
        ks.capture = KBufferCapture::Stencil;
        ks.multisample = multisample;
        KBuffer stencil(ks);
        int bad = 0;
        for (int d = 0; d < kDirections; ++d) {
            const BundleView v = bundleView(frame.gpuScene().bounds(), bundleDirection(std::uint64_t(d)),
                                            bundleJitter(std::uint64_t(d)), kSize);
            atomic.capture(frame, atlas, v, timers);
            stencil.capture(frame, atlas, v, timers);
            bad += mismatchedPixels(stencil.readBack(), atomic.readBack(), stencil.k());
        }
        if (best < 0 || bad < best) {
            best = bad;
            probe.multisample = multisample;
        }
    }
    timers.endFrame(false);
    probe.mismatchedPixels = best;
    probe.pixels = kSize * kSize * kDirections;
    probe.exact = best == 0;
    probe.reason = probe.exact
                       ? std::string("stencil routing exact on this driver (GL_MULTISAMPLE ") +
                             (probe.multisample ? "on" : "off") + ", " + std::to_string(probe.samples) + " samples)"
                       : "stencil routing inexact on this driver with " + std::to_string(probe.samples) +
                             " samples: " + std::to_string(best) + " of " + std::to_string(probe.pixels) +
                             " probe pixels differ from the atomic capture (best with GL_MULTISAMPLE " +
                             (probe.multisample ? "on" : "off") + ")";
    return probe;
}

} // namespace

const StencilProbe& stencilProbe(int samples)
{
    // One probe per driver (the renderer string) and sample count for the life of the process.
    static std::map<std::pair<std::string, int>, std::unique_ptr<StencilProbe>> probes;
    const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    samples = std::clamp(samples, 1, maxKBufferSamples());
    auto& p = probes[{r ? r : "", samples}];
    if (!p) p = std::make_unique<StencilProbe>(runStencilProbe(samples));
    return *p;
}

} // namespace bounce::gl
