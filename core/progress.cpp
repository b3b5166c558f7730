#include "core/progress.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include <unistd.h>

namespace bounce::core {

namespace {

constexpr auto kRedrawInterval = std::chrono::milliseconds(100);
constexpr int kBarWidth = 24;

bool silencedByEnvironment()
{
    const char* v = std::getenv("BOUNCE_PROGRESS");
    return v && (std::strcmp(v, "0") == 0 || std::strcmp(v, "off") == 0);
}

} // namespace

Progress::Progress(std::string label, double total, std::string unit)
    : Progress(std::move(label), total, std::move(unit), Output{})
{}

Progress::Progress(std::string label, double total, std::string unit, Output output)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total), out_(output)
{
    if (silencedByEnvironment() || !out_.stream) out_.enabled = false;
    tty_ = out_.terminal < 0 ? isatty(fileno(out_.stream ? out_.stream : stderr)) != 0 : out_.terminal != 0;
    start_ = lastDraw_ = std::chrono::steady_clock::now();
}

Progress::~Progress()
{
    finish();
}

void Progress::add(double amount)
{
    std::lock_guard lock(mutex_);
    done_ += amount;
    report(false);
}

void Progress::set(double done)
{
    std::lock_guard lock(mutex_);
    done_ = done;
    report(false);
}

void Progress::setTotal(double total)
{
    std::lock_guard lock(mutex_);
    total_ = total;
}

void Progress::setNote(const std::string& note)
{
    std::lock_guard lock(mutex_);
    note_ = note;
}

double Progress::done() const
{
    std::lock_guard lock(mutex_);
    return done_;
}

double Progress::seconds() const
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string Progress::si(double value)
{
    static const char* kPrefixes[] = {"", " k", " M", " G", " T", " P"};
    int p = 0;
    double v = value;
    while (std::abs(v) >= 999.5 && p < 5) {
        v /= 1000.0;
        ++p;
    }
    char buf[32];
    const int decimals = std::abs(v) >= 99.95 ? 0 : std::abs(v) >= 9.995 ? 1 : 2;
    std::snprintf(buf, sizeof buf, "%.*f%s", decimals, v, kPrefixes[p]);
    return buf;
}

std::string Progress::clock(double seconds)
{
    if (!std::isfinite(seconds) || seconds < 0.0) return "?";
    char buf[32];
    if (seconds < 59.95) {
        std::snprintf(buf, sizeof buf, "%.*f s", seconds < 9.995 ? 2 : 1, seconds);
        return buf;
    }
    const auto s = static_cast<long long>(std::llround(seconds));
    if (s >= 3600)
        std::snprintf(buf, sizeof buf, "%lld:%02lld:%02lld", s / 3600, (s / 60) % 60, s % 60);
    else
        std::snprintf(buf, sizeof buf, "%lld:%02lld", s / 60, s % 60);
    return buf;
}

std::string Progress::figures(double elapsed) const
{
    const double rate = elapsed > 0.0 ? done_ / elapsed : 0.0;
    const double left = rate > 0.0 && total_ > done_ ? (total_ - done_) / rate : 0.0;
    std::string s = si(rate) + " " + unit_ + "/s, " + clock(elapsed) + " elapsed, ETA " + clock(left);
    if (!note_.empty()) s += ", " + note_;
    return s;
}

void Progress::report(bool force)
{
    if (!out_.enabled || finished_) return;
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double fraction = total_ > 0.0 ? std::clamp(done_ / total_, 0.0, 1.0) : 0.0;
    if (tty_) {
        if (!force && now - lastDraw_ < kRedrawInterval) return;
        lastDraw_ = now;
        const int filled = int(fraction * kBarWidth);
        std::string bar(std::size_t(filled), '#');
        bar.append(std::size_t(kBarWidth - filled), '-');
        // \33[K clears what a longer previous line left behind.
        std::fprintf(out_.stream, "\r%s [%s] %3d%% %s\33[K", label_.c_str(), bar.c_str(), int(fraction * 100.0),
                     figures(elapsed).c_str());
        std::fflush(out_.stream);
        return;
    }
    const int decile = int(fraction * 10.0);
    if (decile <= lastDecile_ || decile >= 10) return; // 100% is said by finish()
    lastDecile_ = decile;
    std::fprintf(out_.stream, "%s: %d%% (%s %s, %s)\n", label_.c_str(), decile * 10, si(done_).c_str(), unit_.c_str(),
                 figures(elapsed).c_str());
    std::fflush(out_.stream);
}

void Progress::finish()
{
    std::lock_guard lock(mutex_);
    if (!out_.enabled || finished_) {
        finished_ = true;
        return;
    }
    const double elapsed = seconds();
    const double rate = elapsed > 0.0 ? done_ / elapsed : 0.0;
    std::string line =
        label_ + ": done, " + si(done_) + " " + unit_ + " in " + clock(elapsed) + " (" + si(rate) + " " + unit_ + "/s)";
    if (!note_.empty()) line += ", " + note_;
    if (tty_)
        std::fprintf(out_.stream, "\r%s\33[K\n", line.c_str());
    else
        std::fprintf(out_.stream, "%s\n", line.c_str());
    std::fflush(out_.stream);
    finished_ = true;
}

} // namespace bounce::core
