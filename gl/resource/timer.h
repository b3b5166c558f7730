// Per-pass GPU time from GL_TIME_ELAPSED timer queries. A frame opens one scope per pass; endFrame()
// reads the results back (blocking: the benchmark wants exact figures, not last frame's) and keeps
// them, so stats() can give the median over the timed frames.
#pragma once

#include <string>
#include <vector>

#include "gl/resource/handle.h"

namespace bounce::gl {

struct QueryDeleter { void operator()(unsigned id) const; };

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
        Scope(Scope&& o) noexcept : active_(o.active_), serialize_(o.serialize_) { o.active_ = false; }
        ~Scope();
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        friend class PassTimers;
        Scope(bool active, bool serialize) : active_(active), serialize_(serialize) {}
        bool active_;
        bool serialize_; // wait for the pass's work before the next pass's query begins
    };

    // Opens a timed scope for `pass` (queries cannot nest: one pass at a time).
    Scope scope(const std::string& pass);
    // Collects this frame's query results; when `keep` is false (warm-up frames) they are dropped.
    void endFrame(bool keep = true);
    // Passes in the order first seen, with statistics over the kept frames.
    std::vector<PassStat> stats() const;
    // Medians of the last kept frame only (the demo's panel).
    std::vector<PassStat> lastFrame() const;
    void clear();

private:
    struct Pending { std::string pass; std::size_t query; };
    std::vector<Handle<QueryDeleter>> pool_;
    std::vector<Pending> pending_;
    std::vector<std::string> order_;
    std::vector<std::vector<double>> samples_; // per pass, per kept frame (ms, summed within a frame)
    std::vector<double> last_;
    bool serialize_ = false; // llvmpipe: each scope waits for its work (timer.cpp)
    int pass(const std::string& name);
};

} // namespace bounce::gl
