// Per-pass GPU time from GL_TIME_ELAPSED timer queries (query.h); on a software rasteriser (llvmpipe),
// whose queries miss work, the wall-clock time between glFinish calls around the scope (timer.cpp).
// The driver also counts the pass's shader invocations (GL_ARB_pipeline_statistics_query), which with
// the pass's declared PassCost give the work it did (app/roofline.h). A frame opens one scope per pass;
// endFrame() reads the results back (blocking: the benchmark wants exact figures, not last frame's)
// and keeps them, so stats() can give the median over the timed frames. Each scope is also a KHR_debug
// group named after the pass, so a capture (RenderDoc, apitrace) shows the frame pass by pass.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "gl/resource/query.h"

namespace bounce::gl {

// What one shader invocation of a pass does, counted from the shader's own loops: a pass declares it when
// it opens its timed scope, and the invocations that ran are counted by the driver (pipeline statistics:
// fragment and compute shader invocations), so work = invocations x cost per invocation. A pass opened
// several times in a frame (per level, per light) declares each scope's own cost. `bytesFixed` is work
// that does not scale with invocations (a clear, a buffer copy, vertex streams).
struct PassCost {
    double flops = 0.0;        // arithmetic per invocation (an FMA counts 2, per component)
    double fetches = 0.0;      // texel fetches / texture samples / image loads per invocation
    double bytesRead = 0.0;    // memory read per invocation (textures, images, buffers, framebuffer)
    double bytesWritten = 0.0; // memory written per invocation (render targets, images, buffers)
    // Words read from uniform blocks (or buffers) at an address every invocation shares, as a gather's loop
    // reads its VPLs: free on a GPU (broadcast), a lane-by-lane load on llvmpipe (Ceilings: *GuniformWords).
    double uniformWords = 0.0;
    double bytesFixed = 0.0; // per scope, not per invocation
    double flopsFixed = 0.0; // per scope: work counted by the pass itself (a tree walk's visited nodes)
    double fetchesFixed = 0.0;
    double uniformWordsFixed = 0.0;
    double triangles = 0.0; // per scope: triangles the rasteriser sets up (drawn geometry)
    bool declared() const
    {
        return flops > 0.0 || fetches > 0.0 || bytesRead > 0.0 || bytesWritten > 0.0 || uniformWords > 0.0 ||
               bytesFixed > 0.0 || flopsFixed > 0.0 || fetchesFixed > 0.0 || uniformWordsFixed > 0.0 || triangles > 0.0;
    }
};

// `count` times the per-invocation work `each` (a kernel's invocations, or the items its loops visit), as
// per-scope work: how a scope that runs several different kernels declares each one's share.
PassCost kernelWork(double count, const PassCost& each);

// The work a pass did in one frame: invocations from the driver, the rest from PassCost.
struct PassWork {
    double fragmentInvocations = 0.0;
    double computeInvocations = 0.0;
    double flops = 0.0;
    double fetches = 0.0;
    double bytes = 0.0;        // read + written
    double uniformWords = 0.0; // read from uniform blocks at shared addresses (PassCost::uniformWords)
    double triangles = 0.0;    // set up by the rasteriser
    bool costDeclared = false; // every scope of the pass declared a PassCost
    // The invocations the pass declared it runs (PassTimers::Scope::expectFragments/expectComputes), summed
    // over its scopes; unset where a scope of the pass declared none of that kind. Fragments: the pixels of
    // the declared viewports, and the most a rasteriser may count for them (timer.cpp, expectFragments): the
    // driver's count lies between.
    std::optional<double> expectedFragmentInvocations;
    double expectedFragmentInvocationsAtMost = 0.0;
    std::optional<double> expectedComputeInvocations;
};

struct PassStat {
    std::string pass;
    double medianMs = 0.0;
    double minMs = 0.0;
    double maxMs = 0.0;
    int frames = 0;
    PassWork work; // of the median frame (by time); invocations are 0 where the driver cannot count them
};

class PassTimers {
public:
    class Scope {
    public:
        Scope(Scope&& o) noexcept : owner_(o.owner_), query_(o.query_), serialize_(o.serialize_), grouped_(o.grouped_)
        {
            o.owner_ = nullptr;
        }
        ~Scope();
        // Work of this scope known only once it ran (counters the pass reads back), added to its cost.
        void addWork(const PassCost& fixed);
        // The shader invocations the scope runs, where the pass's size says them exactly, added up over the
        // calls: a full-screen fragment pass its viewport (x, y: its corner in the framebuffer), a compute pass
        // each dispatch's groups times its local size (computeInvocations, dispatch.h), the partial groups'
        // idle invocations included. The driver's count must match (tests/gl/invocations_test.cpp), so a
        // dispatch or viewport of the wrong size, or work timed in the wrong scope, fails a test. A pass that
        // rasterises geometry (G-buffer, shadow maps, RSMs, splats, atlases, the k-buffer) declares no
        // fragments: its coverage is known only once the rasteriser ran.
        void expectFragments(int width, int height, int x = 0, int y = 0);
        void expectComputes(double invocations);
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        friend class PassTimers;
        Scope(PassTimers* owner, std::size_t query, bool serialize, bool grouped)
            : owner_(owner), query_(query), serialize_(serialize), grouped_(grouped)
        {}
        // The pending entry is the one whose query is query_ (scopes of a frame use queries 0, 1, ...).
        PassTimers* owner_; // null once moved from
        std::size_t query_; // index into owner_->pool_ (stable while the pool grows)
        bool serialize_;    // wait for the pass's work before the next pass's query begins
        bool grouped_;      // a debug group was pushed: pop it
    };

    // Opens a timed scope for `pass` (queries cannot nest: one pass at a time), inside a debug group
    // named `pass` (glPushDebugGroup, GL_DEBUG_SOURCE_APPLICATION). `cost`: what one invocation of the
    // pass's shader does (PassCost), for its bound (app/roofline.h); the invocations are counted here.
    Scope scope(const std::string& pass, const PassCost& cost = {});
    // Collects this frame's query results; when `keep` is false (warm-up frames) they are dropped.
    void endFrame(bool keep = true);
    // Passes in the order first seen, with statistics over the kept frames.
    std::vector<PassStat> stats() const;
    // Medians of the last kept frame only (the demo's panel).
    std::vector<PassStat> lastFrame() const;
    void clear();

private:
    struct Pending {
        std::string pass;
        std::size_t query;
        PassCost cost;
        std::optional<double> fragments, computes; // expected invocations (Scope::expectFragments...)
        double fragmentsAtMost = 0.0;
    };
    // One scope's queries: elapsed time, and the shader invocations when the driver counts them.
    struct Queries {
        Query time, fragment, compute;
        std::chrono::steady_clock::time_point wallStart{};
        double wallMs = 0.0;
    };
    struct Sample {
        double ms = 0.0;
        PassWork work;
    };
    std::vector<Queries> pool_;
    std::vector<Pending> pending_;
    std::vector<std::string> order_;
    std::vector<std::vector<Sample>> samples_; // per pass, per kept frame (summed within a frame)
    std::vector<double> last_;
    bool serialize_ = false;  // llvmpipe: each scope waits for its work (timer.cpp)
    bool statistics_ = false; // GL_ARB_pipeline_statistics_query: invocations are counted
    int pass(const std::string& name);
};

} // namespace bounce::gl
