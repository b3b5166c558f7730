#include "app/bench_roofline.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace bounce::app {

namespace {

std::string label(const nlohmann::json& rec)
{
    return rec["technique"].get<std::string>() + " (" + rec["settings"].get<std::string>() + ")";
}

} // namespace

bool hasRoofline(const std::vector<BenchRow>& rows)
{
    for (const BenchRow& r : rows)
        for (const auto& p : r.record["passes"])
            if (p.contains("boundMs")) return true;
    return false;
}

std::string rooflineMarkdown(const std::vector<BenchRow>& rows)
{
    std::ostringstream md;
    const nlohmann::json* ceilings = nullptr;
    for (const BenchRow& r : rows)
        if (r.record.contains("ceilings")) ceilings = &r.record["ceilings"];
    md << "## Every pass against its bound\n\n"
          "Each pass's work (shader invocations counted by the driver, times what one invocation does by the"
          " shader's own loops, `PassCost`) at this machine's ceilings, measured by `bounce probe`";
    if (ceilings) {
        char buf[512];
        std::snprintf(
            buf, sizeof buf,
            " (fragment %.1f GFLOP/s, %.1f GB/s, %.2f G fetches/s, %.2f G uniform-block words/s; compute %.1f"
            " GFLOP/s, %.1f GB/s, %.2f G fetches/s, %.2f G uniform-block words/s; %.2f M triangles/s)",
            (*ceilings)["fragmentGflops"].get<double>(), (*ceilings)["fragmentGBps"].get<double>(),
            (*ceilings)["fragmentGfetches"].get<double>(), (*ceilings)["fragmentGuniformWords"].get<double>(),
            (*ceilings)["computeGflops"].get<double>(),
            std::max((*ceilings)["computeImageGBps"].get<double>(), (*ceilings)["computeBufferGBps"].get<double>()),
            (*ceilings)["computeGfetches"].get<double>(), (*ceilings)["computeGuniformWords"].get<double>(),
            (*ceilings)["mtrianglesPerSecond"].get<double>());
        md << buf;
    }
    md << ". `bound ms` is the largest of the arithmetic, fetch, memory, uniform-read and triangle-setup"
          " times; efficiency is bound over measured (1: as fast as the machine allows for that work). A pass"
          " far below 1 is a finding. Passes without a declared cost show `-`. `uniform` is the words a"
          " gather's loop reads from uniform blocks at addresses every invocation shares: a GPU broadcasts"
          " them, llvmpipe loads them lane by lane.\n\n"
          "| scene | render | pass | ms | bound ms | efficiency | limiter | GFLOP | MB | M fetches |"
          " M uniform words |\n"
          "|---|---|---|---:|---:|---:|---|---:|---:|---:|---:|\n";
    for (const BenchRow& r : rows)
        for (const auto& p : r.record["passes"]) {
            char buf[512];
            if (p.contains("boundMs"))
                std::snprintf(buf, sizeof buf,
                              "| %s | %s | %s | %.3f | %.3f | %.2f | %s | %.3f | %.2f | %.2f | %.2f |\n",
                              r.scene.c_str(), label(r.record).c_str(), p["pass"].get<std::string>().c_str(),
                              p["medianMs"].get<double>(), p["boundMs"].get<double>(), p["efficiency"].get<double>(),
                              p["limiter"].get<std::string>().c_str(), p["flops"].get<double>() * 1e-9,
                              p["bytes"].get<double>() * 1e-6, p["fetches"].get<double>() * 1e-6,
                              p.value("uniformWords", 0.0) * 1e-6);
            else
                std::snprintf(buf, sizeof buf, "| %s | %s | %s | %.3f | - | - | - | - | - | - | - |\n", r.scene.c_str(),
                              label(r.record).c_str(), p["pass"].get<std::string>().c_str(),
                              p["medianMs"].get<double>());
            md << buf;
        }
    md << "\n![roofline](roofline.png)\n\n";
    return md.str();
}

std::string rooflineCsv(const std::vector<BenchRow>& rows)
{
    std::ostringstream csv;
    csv << "scene,technique,settings,pass,ms,bound_ms,efficiency,limiter,flops,bytes,fetches,triangles,"
           "fragment_invocations,compute_invocations,fragment_gflops,compute_gflops,fragment_gbps,compute_gbps,"
           "uniform_words\n";
    for (const BenchRow& r : rows) {
        if (!r.record.contains("ceilings")) continue;
        const nlohmann::json& c = r.record["ceilings"];
        for (const auto& p : r.record["passes"]) {
            if (!p.contains("boundMs")) continue;
            char buf[1024];
            std::snprintf(buf, sizeof buf,
                          "%s,%s,\"%s\",%s,%.6g,%.6g,%.6g,%s,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n",
                          r.scene.c_str(), r.record["technique"].get<std::string>().c_str(),
                          r.record["settings"].get<std::string>().c_str(), p["pass"].get<std::string>().c_str(),
                          p["medianMs"].get<double>(), p["boundMs"].get<double>(), p["efficiency"].get<double>(),
                          p["limiter"].get<std::string>().c_str(), p["flops"].get<double>(), p["bytes"].get<double>(),
                          p["fetches"].get<double>(), p["triangles"].get<double>(),
                          p["fragmentInvocations"].get<double>(), p["computeInvocations"].get<double>(),
                          c["fragmentGflops"].get<double>(), c["computeGflops"].get<double>(),
                          c["fragmentGBps"].get<double>(),
                          std::max(c["computeImageGBps"].get<double>(), c["computeBufferGBps"].get<double>()),
                          p.value("uniformWords", 0.0));
            csv << buf;
        }
    }
    return csv.str();
}

std::string plotPython()
{
    const char* python = std::getenv("BOUNCE_PYTHON");
    return python && *python ? python : "/usr/bin/python3";
}

int runPlotScript(const std::string& script, const std::filesystem::path& input, const std::filesystem::path& png)
{
    const std::string plot = plotPython() + " '" + (std::filesystem::path(BOUNCE_SOURCE_ROOT) / script).string() +
                             "' '" + input.string() + "' '" + png.string() + "'";
    const int rc = std::system(plot.c_str());
    if (rc != 0) std::fprintf(stderr, "bounce bench: %s failed (%d): %s\n", script.c_str(), rc, plot.c_str());
    return rc;
}

int plotRoofline(const std::filesystem::path& out)
{
    return runPlotScript("bench/plot_roofline.py", out / "roofline.csv", out / "roofline.png");
}

} // namespace bounce::app
