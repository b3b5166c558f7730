// Progress of long work (reference renders, benchmarks, asset generation) on stderr.
//
// On a terminal: one line redrawn in place at most 10 times a second, with a bar, the percentage, the
// rate (units per second, SI prefixes) and the estimated time left. Not on a terminal (logs, ctest,
// pipes): one line per 10% crossed and a last line with the total and the rate, so logs stay short.
// BOUNCE_PROGRESS=0 in the environment silences every bar (tests, scripts that parse stderr).
// All members are thread-safe; the total may change while running (progressive work with a noise
// target only knows its total as an estimate that improves).
#pragma once

#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>

namespace bounce::core {

class Progress {
public:
    struct Output {
        std::FILE* stream = stderr;
        int terminal = -1;   // -1: ask isatty(stream); 0: log lines; 1: the redrawn bar
        bool enabled = true; // false: nothing is ever written (BOUNCE_PROGRESS=0 forces this)
    };

    Progress(std::string label, double total, std::string unit);
    Progress(std::string label, double total, std::string unit, Output output);
    ~Progress(); // finish()
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void add(double amount);
    void set(double done);
    void setTotal(double total);
    void setNote(const std::string& note); // shown after the figures, e.g. "noise 1.4%"
    // Writes the last line (the total, the time, the rate) once; later calls do nothing.
    void finish();

    double done() const;
    double seconds() const; // since construction

    // "1.23 M", "456 k", "12.0": three significant digits with an SI prefix.
    static std::string si(double value);
    // "0.42 s", "12.3 s" under a minute, then "12:34", "1:02:03".
    static std::string clock(double seconds);

private:
    void report(bool force);
    std::string figures(double elapsed) const;

    std::string label_, unit_, note_;
    double total_ = 0.0, done_ = 0.0;
    Output out_;
    bool tty_ = false, finished_ = false;
    int lastDecile_ = 0;
    std::chrono::steady_clock::time_point start_, lastDraw_;
    mutable std::mutex mutex_;
};

} // namespace bounce::core
