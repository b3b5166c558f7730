#include "gl/resource/timer.h"

#include <algorithm>
#include <stdexcept>

#include "gl/context/context.h"
#include "gl/gl.h"

namespace bounce::gl {

PassTimers::Scope::~Scope()
{
    if (!owner_) return;
    owner_->pool_[query_].end();
    // llvmpipe rasterises a pass's draws later than the calls, often inside the next pass's query (a
    // compute pass that reads the result flushes them there): the upsampling after a 240 ms gather read
    // 27 ms instead of 20. Waiting here keeps each pass's work inside its own interval. A GPU's queries
    // are ordered with its work, and there the wait would only add bubbles.
    if (serialize_) glFinish();
    if (grouped_) glPopDebugGroup();
}

int PassTimers::pass(const std::string& name)
{
    const auto it = std::find(order_.begin(), order_.end(), name);
    if (it != order_.end()) return int(it - order_.begin());
    order_.push_back(name);
    samples_.emplace_back();
    return int(order_.size() - 1);
}

PassTimers::Scope PassTimers::scope(const std::string& name)
{
    const std::size_t q = pending_.size();
    if (pool_.empty()) {
        serialize_ = softwareRasterizer();
        // llvmpipe answers the first TIME_ELAPSED query of a context with a timestamp (minutes to hours)
        // instead of an interval, also when nothing ran inside it; a query around a clear of a 1x1
        // framebuffer, read at once, takes that answer before any pass does (harmless elsewhere).
        pool_.emplace_back(GL_TIME_ELAPSED, "pass-timer.0");
        GLuint tex = 0, fbo = 0;
        GLint previous = 0;
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
        glCreateTextures(GL_TEXTURE_2D, 1, &tex);
        glTextureStorage2D(tex, 1, GL_RGBA8, 1, 1);
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
        {
            auto first = pool_.front().scope();
            glClear(GL_COLOR_BUFFER_BIT);
        }
        (void)pool_.front().result();
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(previous));
        glDeleteFramebuffers(1, &fbo);
        glDeleteTextures(1, &tex);
    }
    if (q == pool_.size()) pool_.emplace_back(GL_TIME_ELAPSED, "pass-timer." + std::to_string(q));
    pending_.push_back({name, q});
    // The group opens before the query and closes after it, so the capture's group holds the whole
    // timed interval. Present in every GL 4.3+ context; a message only with KHR_debug output enabled.
    const bool grouped = glPushDebugGroup != nullptr;
    if (grouped) glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, GLsizei(name.size()), name.c_str());
    pool_[q].begin();
    // llvmpipe takes the begin timestamp when it next flushes its queued work, but runs a compute dispatch
    // inside the glDispatchCompute call: a pass that starts with a dispatch would otherwise begin its
    // interval after its own work (a 8 s micro-rendering gather read 0.1 ms).
    if (serialize_) glFinish();
    return Scope(this, q, serialize_, grouped);
}

void PassTimers::endFrame(bool keep)
{
    std::vector<double> frame(order_.size(), 0.0);
    std::vector<bool> seen(order_.size(), false);
    for (const Pending& p : pending_) {
        const std::uint64_t ns = pool_[p.query].result();
        const int i = pass(p.pass);
        if (std::size_t(i) >= frame.size()) {
            frame.resize(i + 1, 0.0);
            seen.resize(i + 1, false);
        }
        frame[i] += double(ns) * 1e-6;
        seen[i] = true;
    }
    pending_.clear();
    last_ = frame;
    if (!keep) return;
    for (std::size_t i = 0; i < frame.size(); ++i)
        if (seen[i]) samples_[i].push_back(frame[i]);
}

std::vector<PassStat> PassTimers::stats() const
{
    std::vector<PassStat> out;
    for (std::size_t i = 0; i < order_.size(); ++i) {
        std::vector<double> s = samples_[i];
        if (s.empty()) continue;
        std::sort(s.begin(), s.end());
        const std::size_t n = s.size();
        const double median = n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
        out.push_back({order_[i], median, s.front(), s.back(), int(n)});
    }
    return out;
}

std::vector<PassStat> PassTimers::lastFrame() const
{
    std::vector<PassStat> out;
    for (std::size_t i = 0; i < last_.size() && i < order_.size(); ++i)
        out.push_back({order_[i], last_[i], last_[i], last_[i], 1});
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
