#include "app/bench_report.h"

#include "app/bench_roofline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include "app/render_job.h"
#include "core/image.h"

namespace bounce::app {

namespace {

std::string csvField(const std::string& s)
{
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

// The time of a row's image: its still frames times the median frame (the path tracer: its CPU time).
double imageMs(const nlohmann::json& record)
{
    return record.value("imageMs", record["totalMs"].get<double>());
}

std::string rendererOf(const BenchRow& r)
{
    return r.record.value("renderer", "");
}

// The Pareto fronts, computed here once for every reader (report.md's table, results.json's "pareto",
// results.csv's pareto_own and pareto_full, plot_speed_error.py, report.html): per scene and image size,
// the rows that no other row beats in both the time of the image and the relative RMSE, against the row's
// own light paths ("own") and against `full` ("full"). A row without a finite error is on no front.
// Rows timed on different GL renderers (a merged run of shards on several machines, app/bench_shard.h)
// are on fronts of their own: their times do not compare.
void markParetoFronts(std::vector<BenchRow>& rows)
{
    const auto mark = [&](const char* key, double BenchRow::*error) {
        // A camera-path row's error is of moving frames, not of an image: it is on no front.
        const auto on = [&](const BenchRow& r) {
            return std::isfinite(r.*error) && std::isfinite(imageMs(r.record)) && !r.record.contains("sequence");
        };
        for (BenchRow& a : rows) {
            bool front = on(a);
            for (const BenchRow& b : rows) {
                if (!front) break;
                if (&a == &b || !on(b) || b.scene != a.scene || b.size != a.size || rendererOf(b) != rendererOf(a))
                    continue;
                const double ta = imageMs(a.record), tb = imageMs(b.record);
                front = !(tb <= ta && b.*error <= a.*error && (tb < ta || b.*error < a.*error));
            }
            a.record["pareto"][key] = front;
        }
    };
    mark("own", &BenchRow::relRmseOwn);
    mark("full", &BenchRow::relRmseFull);
}

std::string csvText(const BenchConfig& config, const std::vector<BenchRow>& rows)
{
    std::ostringstream csv;
    csv << "scene,technique,params,size,light_paths,total_ms,rel_rmse_own,rel_rmse_full,rmse_own,ssim_own,baseline,"
           "rel_rmse_baseline,flicker,nonfinite_values,passes";
    for (const std::string& p : config.compareTo) csv << ",rel_rmse_" << p;
    // camera_path: the run's path file (bench "path"), empty for a still run; such a row's errors are the
    // means over its measured moving frames, and its flicker the pairs' (see report.md's camera paths).
    csv << ",rel_rmse_direct_light,image_ms,pareto_own,pareto_full,renderer,camera_path\n";
    for (const BenchRow& r : rows) {
        csv << csvField(r.scene) << "," << r.technique << "," << csvField(r.settings) << "," << r.size << ","
            << r.lightPaths << "," << r.totalMs << "," << r.relRmseOwn << "," << r.relRmseFull << "," << r.rmseOwn
            << "," << r.ssimOwn << "," << csvField(r.baseline) << "," << r.relRmseBaseline << "," << r.flicker << ","
            << r.nonFiniteValues << "," << csvField(r.passes);
        for (double v : r.relRmseCompareTo) csv << "," << v;
        const nlohmann::json& front = r.record.value("pareto", nlohmann::json::object());
        csv << "," << r.relRmseDirectLight << "," << imageMs(r.record) << "," << int(front.value("own", false)) << ","
            << int(front.value("full", false)) << "," << csvField(rendererOf(r)) << ","
            << csvField(r.record.contains("sequence") ? r.record["sequence"]["path"].get<std::string>() : "") << "\n";
    }
    return csv.str();
}

// One row of a scene's table: technique, parameters, size, light paths, ms, errors, SSIM, baseline, flicker.
void tableRow(std::ostringstream& md, const nlohmann::json& rec, const std::vector<std::string>& compareTo)
{
    const std::string lp = rec["lightPaths"];
    char buf[512];
    std::string baseline = "-", flicker = "-";
    if (rec.contains("baseline")) {
        std::snprintf(buf, sizeof buf, "%.4f vs %s (%s)", rec["baseline"]["relativeRmseIndirect"].get<double>(),
                      rec["baseline"]["technique"].get<std::string>().c_str(),
                      rec["baseline"]["settings"].get<std::string>().c_str());
        baseline = buf;
    }
    if (rec.contains("temporal")) {
        std::snprintf(buf, sizeof buf, "%.4f", rec["temporal"]["meanFrameDifference"].get<double>());
        flicker = buf;
    }
    std::snprintf(buf, sizeof buf, "| %s | %s | %s | %s | %.3f | %.4f | %.4f |",
                  rec["technique"].get<std::string>().c_str(), rec["settings"].get<std::string>().c_str(),
                  rec["size"].get<std::string>().c_str(), lp.c_str(), rec["totalMs"].get<double>(),
                  rec["error"][lp]["relativeRmse"].get<double>(), rec["error"]["full"]["relativeRmse"].get<double>());
    md << buf;
    for (const std::string& p : compareTo) {
        std::snprintf(buf, sizeof buf, " %.4f |", rec["error"][p]["relativeRmse"].get<double>());
        md << buf;
    }
    std::string directLight = "-";
    if (rec["error"].contains("directLight")) {
        std::snprintf(buf, sizeof buf, "%.4f", rec["error"]["directLight"]["relativeRmse"].get<double>());
        directLight = buf;
    }
    std::snprintf(buf, sizeof buf, " %s | %.4f | %s | %s |\n", directLight.c_str(),
                  rec["error"][lp]["ssim"].get<double>(), baseline.c_str(), flicker.c_str());
    md << buf;
}

// The per-pass GPU ms of a scene's renders: one row per pass, one column per render.
void passTable(std::ostringstream& md, const std::vector<const nlohmann::json*>& recs)
{
    std::vector<std::string> passes;
    for (const nlohmann::json* rec : recs)
        for (const auto& p : (*rec)["passes"])
            if (std::find(passes.begin(), passes.end(), p["pass"].get<std::string>()) == passes.end())
                passes.push_back(p["pass"]);
    md << "| pass |";
    for (const nlohmann::json* rec : recs)
        md << " " << (*rec)["technique"].get<std::string>() << " (" << (*rec)["settings"].get<std::string>() << ") |";
    md << "\n|---|";
    for (std::size_t i = 0; i < recs.size(); ++i) md << "---:|";
    md << "\n";
    for (const auto& pass : passes) {
        md << "| " << pass << " |";
        for (const nlohmann::json* rec : recs) {
            std::string cell = " - |";
            for (const auto& p : (*rec)["passes"])
                if (p["pass"] == pass) {
                    char buf[64];
                    std::snprintf(buf, sizeof buf, " %.3f |", p["medianMs"].get<double>());
                    cell = buf;
                }
            md << cell;
        }
        md << "\n";
    }
}

// The counters of a scene's renders (photons, clusters, cut size...): one row per counter, one column per
// render; nothing when no render reports one.
void counterTable(std::ostringstream& md, const std::vector<const nlohmann::json*>& recs)
{
    std::vector<std::string> names;
    for (const nlohmann::json* rec : recs)
        if (rec->contains("counters"))
            for (const auto& [name, value] : (*rec)["counters"].items())
                if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    if (names.empty()) return;
    md << "\n### counters\n\n| counter |";
    for (const nlohmann::json* rec : recs)
        md << " " << (*rec)["technique"].get<std::string>() << " (" << (*rec)["settings"].get<std::string>() << ") |";
    md << "\n|---|";
    for (std::size_t i = 0; i < recs.size(); ++i) md << "---:|";
    md << "\n";
    for (const auto& name : names) {
        md << "| " << name << " |";
        for (const nlohmann::json* rec : recs) {
            std::string cell = " - |";
            if (rec->contains("counters") && (*rec)["counters"].contains(name)) {
                char buf[64];
                std::snprintf(buf, sizeof buf, " %.6g |", (*rec)["counters"][name].get<double>());
                cell = buf;
            }
            md << cell;
        }
        md << "\n";
    }
}

// The scene's Pareto front against `full` (markParetoFronts), per image size, fastest first: what
// report.html's plot and speed_error.png mark.
void paretoTable(std::ostringstream& md, const std::vector<const nlohmann::json*>& recs)
{
    std::vector<const nlohmann::json*> front;
    for (const nlohmann::json* r : recs)
        if (r->value("pareto", nlohmann::json::object()).value("full", false)) front.push_back(r);
    std::stable_sort(front.begin(), front.end(), [](const nlohmann::json* a, const nlohmann::json* b) {
        const std::string sa = (*a)["size"].get<std::string>(), sb = (*b)["size"].get<std::string>();
        return sa != sb ? sa < sb : imageMs(*a) < imageMs(*b);
    });
    md << "\n### Pareto front\n\n| technique | parameters | size | ms to the image | frames | rel. RMSE (full) |\n"
          "|---|---|---|---:|---:|---:|\n";
    for (const nlohmann::json* r : front) {
        char buf[512];
        std::snprintf(buf, sizeof buf, "| %s | %s | %s | %.1f | %d | %.4f |\n",
                      (*r)["technique"].get<std::string>().c_str(), (*r)["settings"].get<std::string>().c_str(),
                      (*r)["size"].get<std::string>().c_str(), imageMs(*r), r->value("imageFrames", 1),
                      (*r)["error"]["full"]["relativeRmse"].get<double>());
        md << buf;
    }
}

// The camera-path runs of a scene (bench "path"): per run its mean frame, its error over the measured
// frames (mean, over the path's second half, worst), the flicker and, with "stillFrames", the ratio of
// the moving frames' error to the still images'.
void pathTable(std::ostringstream& md, const std::vector<const nlohmann::json*>& recs)
{
    md << "\n### camera paths\n\nOne frame per step, no still frames; frames iK and iK+1 against path-tracer "
          "references of their own camera (the technique's light paths); flicker: the RMS of the change of the "
          "error image from frame iK to iK+1 over the references' mean (the pairs' mean, and that of the pairs "
          "in the path's second half).\n\n| technique | parameters | size | path | indirect scale | frames | "
          "ms per frame | rel. RMSE mean | second half | worst | flicker | second half | moving / still |\n"
          "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const nlohmann::json* r : recs) {
        const nlohmann::json& q = (*r)["sequence"];
        std::string ratio = "-";
        char buf[1024];
        if (q.contains("meanStillRatio")) {
            std::snprintf(buf, sizeof buf, "%.2f (worst %.2f, second half %.2f, %d still frames)",
                          q["meanStillRatio"].get<double>(), q["worstStillRatio"].get<double>(),
                          q.value("secondHalfStillRatio", double(NAN)), q["stillFrames"].get<int>());
            ratio = buf;
        }
        std::snprintf(buf, sizeof buf,
                      "| %s | %s | %s | %s | %d | %d | %.3f | %.4f | %.4f | %.4f | %.4f | %.4f | %s |\n",
                      (*r)["technique"].get<std::string>().c_str(), (*r)["settings"].get<std::string>().c_str(),
                      (*r)["size"].get<std::string>().c_str(), q["path"].get<std::string>().c_str(),
                      q["indirectScale"].get<int>(), q["frameCount"].get<int>(), q["meanMs"].get<double>(),
                      q["meanRelativeRmse"].get<double>(), q["secondHalfMeanRelativeRmse"].get<double>(),
                      q["worstRelativeRmse"].get<double>(), q["flicker"].get<double>(),
                      q.value("secondHalfFlicker", double(NAN)), ratio.c_str());
        md << buf;
    }
}

// The ray-casting table: Embree's and the GPU's rays per second on the same rays.
std::string raysMarkdown(const std::vector<SceneRays>& rays)
{
    std::ostringstream md;
    md << "## GPU ray casting against Embree\n\nThe same closest-hit rays cast by the frame's GPU ray caster"
          " (compute and fragment shaders) and by Embree on the CPU (app/ray_throughput.h); on llvmpipe both run"
          " on the same cores.\n\n| scene | rays | count | Embree Mray/s | GPU compute Mray/s | GPU fragment Mray/s |"
          " Embree / GPU compute | same triangle |\n|---|---|---:|---:|---:|---:|---:|---:|\n";
    md << std::fixed;
    for (const SceneRays& s : rays)
        for (const RayThroughput& f : s.figures)
            md << "| " << s.scene << " | " << f.kind << " | " << f.rays << " | " << std::setprecision(2)
               << f.embreeRaysPerS * 1e-6 << " | " << f.computeRaysPerS * 1e-6 << " | " << f.fragmentRaysPerS * 1e-6
               << " | " << f.embreeRaysPerS / f.computeRaysPerS << " | " << std::setprecision(2) << 100.0 * f.agreement
               << "% |\n";
    md << "\n";
    return md.str();
}

// A scene's still runs: the table of errors, the per-pass GPU ms, the counters and the Pareto front.
void stillTables(std::ostringstream& md, const std::vector<const nlohmann::json*>& recs, const BenchConfig& config)
{
    md << "\n| technique | parameters | size | light paths | ms | rel. RMSE (own) | rel. RMSE (full) |";
    for (const std::string& p : config.compareTo) md << " rel. RMSE (" << p << ") |";
    md << " rel. RMSE of the frame's direct light (direct) | SSIM (own) | rel. RMSE vs baseline (indirect) | "
          "flicker "
          "|\n|---|---|---|---|---:|---:|---:|";
    for (std::size_t i = 0; i < config.compareTo.size(); ++i) md << "---:|";
    md << "---:|---:|---|---:|\n";
    for (const nlohmann::json* rec : recs) tableRow(md, *rec, config.compareTo);
    md << "\n### per-pass GPU ms\n\n";
    passTable(md, recs);
    counterTable(md, recs);
    paretoTable(md, recs);
}

std::string markdownText(const BenchConfig& config, const std::vector<BenchRow>& rows, const gl::ContextInfo& context,
                         const std::vector<std::string>& notes)
{
    std::ostringstream md;
    md << "# Bounce benchmark\n\n";
    // What a reader must know before the tables: a merge's missing tasks, several renderers' timings.
    for (const std::string& note : notes) md << "**" << note << "**\n\n";
    md << "GL renderer: " << context.renderer << " (" << context.platform << "). " << config.width << "x"
       << config.height << " unless a row says otherwise, " << config.warmup << " warm-up + " << config.frames
       << " timed frames (median GPU ms). Timings compare only within this run. Errors leave out the pixels that see"
          " an emitter directly (and a one-pixel margin): emission is the same exact G-buffer value in every"
          " technique, and its edges alias against the box-filtered references.\n\n";
    for (const BenchRow& r : rows)
        if (r.nonFiniteValues > 0)
            md << "**Failed: " << r.technique << " (" << r.settings << ") on " << r.scene << " wrote "
               << r.nonFiniteValues << " NaN/Inf values; its error figures are infinite.**\n\n";
    for (const auto& sceneName : config.sceneNames) {
        std::vector<const nlohmann::json*> recs, paths;
        for (const BenchRow& r : rows)
            if (r.scene == sceneName) (r.record.contains("sequence") ? paths : recs).push_back(&r.record);
        md << "## " << sceneName << "\n";
        // A scene of camera-path runs alone has no still table.
        if (!recs.empty()) stillTables(md, recs, config);
        if (!paths.empty()) pathTable(md, paths);
        md << "\n";
    }
    if (std::any_of(rows.begin(), rows.end(), [](const BenchRow& r) { return !r.record.contains("sequence"); }))
        md << "![speed against error](speed_error.png)\n";
    return md.str();
}

} // namespace

void writeBenchReport(const std::filesystem::path& out, const BenchConfig& config,
                      const std::vector<BenchRow>& measured, const std::vector<SceneRays>& rays,
                      const gl::ContextInfo& context, const std::vector<std::string>& notes)
{
    std::vector<BenchRow> rows = measured;
    markParetoFronts(rows);
    nlohmann::json results = nlohmann::json::array();
    for (const BenchRow& r : rows) results.push_back(r.record);
    core::writeFileAtomic((out / "results.csv").string(), csvText(config, rows));
    core::writeFileAtomic((out / "results.json").string(), recordText(results));
    std::string md = markdownText(config, rows, context, notes);
    if (!rays.empty()) {
        md += raysMarkdown(rays);
        nlohmann::json j = nlohmann::json::array();
        for (const SceneRays& s : rays) {
            nlohmann::json scene = {{"scene", s.scene}};
            for (const RayThroughput& f : s.figures) scene[f.kind] = f.toJson();
            j.push_back(scene);
        }
        core::writeFileAtomic((out / "rays.json").string(), j.dump(2) + "\n");
    }
    if (hasRoofline(rows)) {
        md += rooflineMarkdown(rows);
        core::writeFileAtomic((out / "roofline.csv").string(), rooflineCsv(rows));
    }
    core::writeFileAtomic((out / "report.md").string(), md);
    writeHtmlReport(out, rows, context, notes);
}

void writeHtmlReport(const std::filesystem::path& out, const std::vector<BenchRow>& rows,
                     const gl::ContextInfo& context, const std::vector<std::string>& notes)
{
    nlohmann::json results = nlohmann::json::array();
    for (const BenchRow& r : rows) results.push_back(r.record);
    const nlohmann::json data = {{"renderer", context.renderer},
                                 {"platform", context.platform},
                                 {"notes", notes},
                                 {"results", nlohmann::json::parse(recordText(results))}};
    core::writeFileAtomic((out / "report-data.js").string(), "window.BOUNCE_REPORT = " + data.dump() + ";\n");
    // The page itself is static: copied from the source tree, so that it is read and tested as code.
    const std::filesystem::path page = std::filesystem::path(BOUNCE_SOURCE_ROOT) / "bench" / "report";
    for (const char* name : {"report.html", "report.js", "report.css"}) {
        std::ifstream in(page / name, std::ios::binary);
        if (!in) throw core::ImageError("cannot read " + (page / name).string());
        std::ostringstream bytes;
        bytes << in.rdbuf();
        core::writeFileAtomic((out / name).string(), bytes.str());
    }
}

int plotSpeedError(const std::filesystem::path& out)
{
    return runPlotScript("bench/plot_speed_error.py", out / "results.csv", out / "speed_error.png");
}

int plotConvergence(const std::filesystem::path& out)
{
    return runPlotScript("bench/plot_convergence.py", out / "results.json", out / "convergence.png");
}

} // namespace bounce::app

namespace bounce::app {

int finishBenchReport(const std::filesystem::path& out, const std::vector<BenchRow>& rows)
{
    // Camera-path rows are not on the speed plot (their error is of moving frames): a config of paths alone
    // has none.
    const bool still =
        std::any_of(rows.begin(), rows.end(), [](const BenchRow& r) { return !r.record.contains("sequence"); });
    int rc = still ? plotSpeedError(out) : 0;
    std::printf("wrote %s/{results.csv,results.json,report.md,report.html%s}\n", out.string().c_str(),
                !still    ? ""
                : rc == 0 ? ",speed_error.png"
                          : "; not speed_error.png: the plot script failed");
    if (std::any_of(rows.begin(), rows.end(), [](const BenchRow& r) { return r.record.contains("curve"); })) {
        rc |= plotConvergence(out);
        std::printf("wrote %s/convergence.png: the curves' error against time and steps, beside the path tracer\n",
                    out.string().c_str());
    }
    if (hasRoofline(rows)) {
        rc |= plotRoofline(out);
        std::printf("wrote %s/{roofline.csv,roofline.png}: every pass against its bound\n", out.string().c_str());
    }
    std::size_t failed = 0;
    for (const BenchRow& r : rows)
        if (r.nonFiniteValues > 0) {
            std::fprintf(stderr, "bounce bench: error: %s (%s) on %s wrote %zu NaN/Inf values\n", r.technique.c_str(),
                         r.settings.c_str(), r.scene.c_str(), r.nonFiniteValues);
            ++failed;
        }
    return rc == 0 && failed == 0 ? 0 : 1;
}

} // namespace bounce::app
