// GL query objects (GL_SAMPLES_PASSED, GL_ANY_SAMPLES_PASSED, GL_PRIMITIVES_GENERATED, GL_TIME_ELAPSED...),
// move-only and labelled: begin/end around the work, read the result as a 64-bit count (nanoseconds for
// GL_TIME_ELAPSED). PassTimers (timer.h) is built on these.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "gl/resource/handle.h"

namespace bounce::gl {

struct QueryDeleter {
    void operator()(unsigned id) const;
};

// Thrown on misuse: begin on an active query, end on an idle one, a result before any end.
struct QueryError : std::logic_error {
    using std::logic_error::logic_error;
};

class Query {
public:
    // Ends the query when it goes out of scope (one begin/end pair around a block of work).
    class Scope {
    public:
        Scope(Scope&& o) noexcept : query_(o.query_) { o.query_ = nullptr; }
        ~Scope()
        {
            if (query_ && query_->active()) query_->end();
        }
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        friend class Query;
        explicit Scope(Query* q) : query_(q) {}
        Query* query_;
    };

    Query() = default;
    // target: GL_SAMPLES_PASSED, GL_ANY_SAMPLES_PASSED, GL_PRIMITIVES_GENERATED, GL_TIME_ELAPSED, ...
    Query(unsigned target, const std::string& label);
    Query(Query&&) noexcept = default;
    Query& operator=(Query&&) noexcept = default;

    unsigned id() const { return handle_.id(); }
    unsigned target() const { return target_; }
    explicit operator bool() const { return bool(handle_); }
    bool active() const { return active_; }

    // One query of a target may be active at a time (per index); GL refuses a second one.
    void begin();
    void end();
    // begin() now, end() when the returned scope ends. Keep the Query alive and unmoved meanwhile.
    [[nodiscard]] Scope scope();
    // Without waiting: whether the last ended query's result has arrived.
    bool resultAvailable() const;
    // Waits for the last ended query's result.
    std::uint64_t result() const;

private:
    Handle<QueryDeleter> handle_;
    unsigned target_ = 0;
    std::string label_; // set at the first begin() (pipeline-statistics queries)
    bool active_ = false;
    bool ended_ = false;
};

} // namespace bounce::gl
