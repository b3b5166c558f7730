// The roofline part of the bench report (issue "every pass against its own bound"): for every render whose
// record has pass bounds (app/roofline.h; the renderer's ceilings cached by `bounce probe` or
// `bounce bench --roofline`), a table of each pass's time, bound, efficiency and limiter, the same rows in
// roofline.csv, and roofline.png (bench/plot_roofline.py: achieved throughput against arithmetic intensity
// under the measured ceilings).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "app/bench_run.h"

namespace bounce::app {

// True when at least one record has bounds (the report then has the section and the files).
bool hasRoofline(const std::vector<BenchRow>& rows);
std::string rooflineMarkdown(const std::vector<BenchRow>& rows);
std::string rooflineCsv(const std::vector<BenchRow>& rows);
// Runs the plot script on out/roofline.csv into out/roofline.png; returns its exit status.
int plotRoofline(const std::filesystem::path& out);

// The Python the plot scripts run under: $BOUNCE_PYTHON, else /usr/bin/python3 (Debian's, with
// python3-matplotlib; a python3 earlier on PATH may be another one without it). A GPU machine's image
// often has matplotlib only in another Python (scripts/device-check.sh picks one that imports it).
std::string plotPython();
// Runs SCRIPT (a path in the source tree) INPUT PNG under plotPython(); prints the command when it fails.
// Its exit status.
int runPlotScript(const std::string& script, const std::filesystem::path& input, const std::filesystem::path& png);

} // namespace bounce::app
