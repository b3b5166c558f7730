// Per-pass GPU time from GL_TIME_ELAPSED timer queries (query.h). A frame opens one scope per pass;
// endFrame() reads the results back (blocking: the benchmark wants exact figures, not last frame's)
// and keeps them, so stats() can give the median over the timed frames. Each scope is also a KHR_debug
// group named after the pass, so a capture (RenderDoc, apitrace) shows the frame pass by pass.
#pragma once

#include <string>
#include <vector>

#include "gl/resource/query.h"

namespace bounce::gl {

struct PassStat {
    std::string pass;
    double medianMs = 0.0;
    double minMs = 0.0;
    double maxMs = 0.0;
    int frames = 0;
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
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        friend class PassTimers;
        Scope(PassTimers* owner, std::size_t query, bool serialize, bool grouped)
            : owner_(owner), query_(query), serialize_(serialize), grouped_(grouped)
        {}
        PassTimers* owner_; // null once moved from
        std::size_t query_; // index into owner_->pool_ (stable while the pool grows)
        bool serialize_;    // wait for the pass's work before the next pass's query begins
        bool grouped_;      // a debug group was pushed: pop it
    };

    // Opens a timed scope for `pass` (queries cannot nest: one pass at a time), inside a debug group
    // named `pass` (glPushDebugGroup, GL_DEBUG_SOURCE_APPLICATION).
    Scope scope(const std::string& pass);
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
    };
    std::vector<Query> pool_;
    std::vector<Pending> pending_;
    std::vector<std::string> order_;
    std::vector<std::vector<double>> samples_; // per pass, per kept frame (ms, summed within a frame)
    std::vector<double> last_;
    bool serialize_ = false; // llvmpipe: each scope waits for its work (timer.cpp)
    int pass(const std::string& name);
};

} // namespace bounce::gl
