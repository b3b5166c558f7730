#include "gl/resource/timer.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "gl/context/context.h"
#include "gl/gl.h"

namespace bounce::gl {

namespace {

// GL_ARB_pipeline_statistics_query (core in 4.6; glad generates the 4.5 core loader, so named here).
constexpr unsigned kFragmentShaderInvocations = 0x82F4;
constexpr unsigned kComputeShaderInvocations = 0x82F5;

} // namespace

PassTimers::Scope::~Scope()
{
    if (!owner_) return;
    Queries& q = owner_->pool_[query_];
    q.time.end();
    if (q.fragment) q.fragment.end();
    if (q.compute) q.compute.end();
    // llvmpipe rasterises a pass's draws later than the calls, often inside the next pass's query (a
    // compute pass that reads the result flushes them there), and its GL_TIME_ELAPSED misses most of a
    // long fragment pass: the probe's FMA kernel read 20 ms against 780 ms of wall-clock time, while short
    // passes agreed within a few percent. On a software rasteriser the work runs on this machine's cores
    // between two glFinish calls, so the wall-clock time between them is the pass's time. A GPU's
    // queries are ordered with its work, and there the waits would only add bubbles.
    if (serialize_) {
        glFinish();
        q.wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - q.wallStart).count();
    }
    if (grouped_) glPopDebugGroup();
}

PassCost kernelWork(double count, const PassCost& each)
{
    PassCost w;
    w.flopsFixed = count * each.flops;
    w.fetchesFixed = count * each.fetches;
    w.bytesFixed = count * (each.bytesRead + each.bytesWritten);
    w.uniformWordsFixed = count * each.uniformWords;
    return w;
}

void PassTimers::Scope::addWork(const PassCost& fixed)
{
    if (!owner_) return;
    PassCost& c = owner_->pending_[query_].cost; // scope q of a frame is pending entry q (scope())
    c.bytesFixed += fixed.bytesFixed;
    c.flopsFixed += fixed.flopsFixed;
    c.fetchesFixed += fixed.fetchesFixed;
    c.uniformWordsFixed += fixed.uniformWordsFixed;
    c.triangles += fixed.triangles;
}

void PassTimers::Scope::expectFragments(int width, int height, int x, int y)
{
    if (!owner_) return;
    Pending& p = owner_->pending_[query_];
    p.fragments = p.fragments.value_or(0.0) + double(width) * double(height);
    // A rasteriser shades whole 2x2 quads; llvmpipe shades and counts whole 4x4 blocks of the framebuffer
    // (16 invocations each, lp_query.c), and the blocks on the diagonal of a full-screen triangle's viewport
    // twice: it draws the triangle clipped to the viewport as two triangles, and a block with pixels of both
    // runs for each. Measured (blocks counted over blocks touched): 1x1 1/1, 4x4 2/1, 16x16 20/16, 37x29
    // 92/80, 64x64 272/256, 128x32 288/256, 107x83 603/567, 200x7 137/100. A diagonal crosses at most
    // bx + by - 1 of the bx x by blocks.
    const auto blocks = [](int first, int count) { return count > 0 ? (first + count + 3) / 4 - first / 4 : 0; };
    const double bx = blocks(x, width), by = blocks(y, height);
    p.fragmentsAtMost += bx > 0 && by > 0 ? 16.0 * (bx * by + bx + by - 1.0) : 0.0;
}

void PassTimers::Scope::expectComputes(double invocations)
{
    if (!owner_) return;
    std::optional<double>& e = owner_->pending_[query_].computes;
    e = e.value_or(0.0) + invocations;
}

int PassTimers::pass(const std::string& name)
{
    const auto it = std::find(order_.begin(), order_.end(), name);
    if (it != order_.end()) return int(it - order_.begin());
    order_.push_back(name);
    samples_.emplace_back();
    return int(order_.size() - 1);
}

PassTimers::Scope PassTimers::scope(const std::string& name, const PassCost& cost)
{
    const std::size_t q = pending_.size();
    if (pool_.empty()) {
        serialize_ = softwareRasterizer();
        statistics_ = hasGlExtension("GL_ARB_pipeline_statistics_query");
        // llvmpipe answers the first TIME_ELAPSED query of a context with a timestamp (minutes to hours)
        // instead of an interval, also when nothing ran inside it; a query around a clear of a 1x1
        // framebuffer, read at once, takes that answer before any pass does (harmless elsewhere).
        pool_.push_back({Query(GL_TIME_ELAPSED, "pass-timer.0"), {}, {}});
        GLuint tex = 0, fbo = 0;
        GLint previous = 0;
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
        glCreateTextures(GL_TEXTURE_2D, 1, &tex);
        glTextureStorage2D(tex, 1, GL_RGBA8, 1, 1);
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
        {
            auto first = pool_.front().time.scope();
            glClear(GL_COLOR_BUFFER_BIT);
        }
        (void)pool_.front().time.result();
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(previous));
        glDeleteFramebuffers(1, &fbo);
        glDeleteTextures(1, &tex);
    }
    if (q == pool_.size()) pool_.push_back({Query(GL_TIME_ELAPSED, "pass-timer." + std::to_string(q)), {}, {}});
    if (statistics_ && !pool_[q].fragment) {
        pool_[q].fragment = Query(kFragmentShaderInvocations, "pass-fragments." + std::to_string(q));
        pool_[q].compute = Query(kComputeShaderInvocations, "pass-computes." + std::to_string(q));
    }
    pending_.push_back({name, q, cost, {}, {}, 0.0});
    // The group opens before the query and closes after it, so the capture's group holds the whole
    // timed interval. Present in every GL 4.3+ context; a message only with KHR_debug output enabled.
    const bool grouped = glPushDebugGroup != nullptr;
    if (grouped) glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, GLsizei(name.size()), name.c_str());
    if (serialize_) {
        glFinish(); // nothing issued before the scope is counted in it
        pool_[q].wallStart = std::chrono::steady_clock::now();
    }
    pool_[q].time.begin();
    if (pool_[q].fragment) pool_[q].fragment.begin();
    if (pool_[q].compute) pool_[q].compute.begin();
    return Scope(this, q, serialize_, grouped);
}

void PassTimers::endFrame(bool keep)
{
    std::vector<Sample> frame(order_.size());
    std::vector<bool> seen(order_.size(), false);
    for (const Pending& p : pending_) {
        const Queries& q = pool_[p.query];
        const int i = pass(p.pass);
        if (std::size_t(i) >= frame.size()) {
            frame.resize(i + 1);
            seen.resize(i + 1, false);
        }
        Sample& s = frame[i];
        if (!seen[i]) {
            s.work.costDeclared = true;
            s.work.expectedFragmentInvocations = p.fragments;
            s.work.expectedFragmentInvocationsAtMost = p.fragmentsAtMost;
            s.work.expectedComputeInvocations = p.computes;
        } else {
            // Declared for the pass only where every scope of it declared.
            const auto add = [](std::optional<double>& sum, const std::optional<double>& e) {
                sum = sum && e ? std::optional<double>(*sum + *e) : std::nullopt;
            };
            add(s.work.expectedFragmentInvocations, p.fragments);
            s.work.expectedFragmentInvocationsAtMost += p.fragmentsAtMost;
            add(s.work.expectedComputeInvocations, p.computes);
        }
        const double queryMs = double(q.time.result()) * 1e-6;
        s.ms += serialize_ ? q.wallMs : queryMs;
        const double fragments = q.fragment ? double(q.fragment.result()) : 0.0;
        const double computes = q.compute ? double(q.compute.result()) : 0.0;
        const double invocations = fragments + computes;
        s.work.fragmentInvocations += fragments;
        s.work.computeInvocations += computes;
        s.work.flops += invocations * p.cost.flops + p.cost.flopsFixed;
        s.work.fetches += invocations * p.cost.fetches + p.cost.fetchesFixed;
        s.work.bytes += invocations * (p.cost.bytesRead + p.cost.bytesWritten) + p.cost.bytesFixed;
        s.work.uniformWords += invocations * p.cost.uniformWords + p.cost.uniformWordsFixed;
        s.work.triangles += p.cost.triangles;
        s.work.costDeclared = s.work.costDeclared && p.cost.declared();
        seen[i] = true;
    }
    pending_.clear();
    last_.assign(frame.size(), 0.0);
    for (std::size_t i = 0; i < frame.size(); ++i) last_[i] = frame[i].ms;
    if (!keep) return;
    for (std::size_t i = 0; i < frame.size(); ++i)
        if (seen[i]) samples_[i].push_back(frame[i]);
}

std::vector<PassStat> PassTimers::stats() const
{
    std::vector<PassStat> out;
    for (std::size_t i = 0; i < order_.size(); ++i) {
        std::vector<Sample> s = samples_[i];
        if (s.empty()) continue;
        std::sort(s.begin(), s.end(), [](const Sample& a, const Sample& b) { return a.ms < b.ms; });
        const std::size_t n = s.size();
        const double median = n % 2 ? s[n / 2].ms : 0.5 * (s[n / 2 - 1].ms + s[n / 2].ms);
        // The work of the median frame (the lower of the two middle ones when n is even).
        out.push_back({order_[i], median, s.front().ms, s.back().ms, int(n), s[(n - 1) / 2].work});
    }
    return out;
}

std::vector<PassStat> PassTimers::lastFrame() const
{
    std::vector<PassStat> out;
    for (std::size_t i = 0; i < last_.size() && i < order_.size(); ++i)
        out.push_back({order_[i], last_[i], last_[i], last_[i], 1, {}});
    return out;
}

void PassTimers::clear()
{
    pending_.clear();
    order_.clear();
    samples_.clear();
    last_.clear();
}

} // namespace bounce::gl
