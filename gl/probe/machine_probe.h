// The machine's ceilings, measured once by small GL kernels (`bounce probe`): what a fragment pass and a
// compute pass can do per second in arithmetic, texel fetches and memory traffic, and how many small
// triangles the rasteriser sets up. Every pass's bound (app/roofline.h) is its work at these ceilings,
// so a pass is judged against this machine rather than against a number from another one.
//
// Measured the way passes are timed (PassTimers: GL_TIME_ELAPSED, on llvmpipe each scope waits for its
// work), median of `repeats` runs after a warm-up, each run repeating the kernel until it lasts 20 ms (a GPU
// runs one in microseconds). The kernels are in glsl/probe/; they are straight-line code where a loop would
// measure the loop (kernels.glsl).
#pragma once

#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace bounce::gl {

struct Ceilings {
    std::string renderer;           // GL_RENDERER of the context that measured them
    double fragmentGflops = 0.0;    // FMA throughput of a full-screen fragment pass
    double computeGflops = 0.0;     // the same kernel as a compute dispatch
    double fragmentGBps = 0.0;      // texelFetch of four RGBA32F inputs + one RGBA32F target
    double computeImageGBps = 0.0;  // texelFetch + imageStore of RGBA32F
    double computeBufferGBps = 0.0; // SSBO vec4 copy
    double fragmentGfetches = 0.0;  // texel fetches per second (cache-resident texture), fragment
    double computeGfetches = 0.0;   //   and compute
    // Uniform-block words a gather's loop reads per second, every invocation the same record at once (a
    // GPU broadcasts them; llvmpipe loads them lane by lane: then they, not the arithmetic, bound a gather).
    double fragmentGuniformWords = 0.0;
    double computeGuniformWords = 0.0;
    double framebufferGBps = 0.0;     // a flat-colour RGBA32F target, written only
    double mtrianglesPerSecond = 0.0; // pixel-sized triangles, flat shaded
    int size = 0;                     // the side of the probe's square targets

    double computeGBps() const { return computeImageGBps > computeBufferGBps ? computeImageGBps : computeBufferGBps; }
    nlohmann::json toJson() const;
    // Throws std::invalid_argument when a field is missing or not a positive number.
    static Ceilings fromJson(const nlohmann::json& j);
};

struct ProbeOptions {
    int size = 1024; // targets are size x size
    int repeats = 5; // timed runs per kernel (after one warm-up)
    // Called after each kernel with its name and how many of `total` are done (progress bars).
    std::function<void(const std::string& kernel, int done, int total)> progress;
};

// Runs every kernel on the current context. Needs GL 4.5 core.
Ceilings probeMachine(const ProbeOptions& options = {});

// The ceilings `bounce probe` measured for the renderer in use, when the application knows them (it reads
// its cache after making a context); nullopt forgets them.
void setKnownCeilings(const std::optional<Ceilings>& ceilings);
// Whether a pass written both as a full-screen fragment pass and as a compute pass runs as fragments (the
// passes' `auto` forms: multiresolution gathers and upsampling, photon interpolation). By the probe's FMA
// ceilings when known: fragments where a fragment pass computes faster (llvmpipe: 58 GFLOP/s against 35),
// compute where the graphics units are few (an NVIDIA H200: 1.8 TFLOP/s against 48). Unknown: by the
// renderer's kind, fragments on a software rasteriser.
bool preferFragmentPasses();

} // namespace bounce::gl
